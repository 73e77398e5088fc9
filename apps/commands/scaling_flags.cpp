// Shared scaling-law flags (see scaling_flags.hpp for the rules).
#include "scaling_flags.hpp"

#include <cmath>
#include <sstream>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/scaling/fit_json.hpp"

namespace craterkit::cli {
namespace {

void check_flag(const std::optional<double>& value, const std::string& flag, bool allow_zero) {
  if (!value) return;
  const bool ok = std::isfinite(*value) && (allow_zero ? *value >= 0.0 : *value > 0.0);
  if (!ok) {
    throw InputError(flag + " " + format_number(*value) + " is not allowed: must be a finite number " +
                     (allow_zero ? ">= 0" : "> 0"));
  }
}

}  // namespace

void add_scaling_flags(CLI::App& app, ScalingFlags& flags) {
  app.add_option(
      "--params", flags.params,
      "Published constant set in data/scaling/ (e.g. jutzi2022_ryugu); explicit flags override it");
  app.add_option("--fit", flags.fit_file, "Scaling law from a fit JSON written by `craterkit fit --out`");
  app.add_option("--group", flags.group,
                 "With --fit of a grouped fit: the group whose law to use, KEY=VALUE[,KEY=VALUE] (e.g. "
                 "friction=0.55,porosity=0.5; values as written in the table)");
  app.add_option("--K1", flags.K1, "Holsapple-form K1 (selects the Holsapple form)");
  app.add_option("--K2", flags.K2, "Holsapple-form K2 (selects the Holsapple form)");
  app.add_option("--H1", flags.H1, "Housen & Holsapple (2011) H1 (selects the HH2011 form)");
  app.add_option("--H2", flags.H2, "Housen & Holsapple (2011) H2 (selects the HH2011 form)");
  app.add_option("--mu", flags.mu, "Velocity exponent mu (1/3 momentum .. 2/3 energy scaling)");
  app.add_option("--nu", flags.nu, "Density exponent nu (about 0.4)");
  app.add_option("--gravity", flags.gravity, "Surface gravity g, m/s^2");
  app.add_option("--target-density", flags.target_density, "Target bulk density rho, kg/m^3");
  app.add_option("--impactor-density", flags.impactor_density, "Impactor density delta, kg/m^3");
  app.add_option("--velocity", flags.velocity, "Impact speed U (normal component), m/s");
}

void add_strength_flag(CLI::App& app, ScalingFlags& flags) {
  app.add_option("--strength", flags.strength, "Target strength Y of the scaling law (cohesion-like), Pa");
}

double require_value(const std::optional<double>& value, const std::string& flag) {
  if (!value) throw InputError(flag + " is required (no constant set or fit gives it)");
  return *value;
}

ScalingInputs resolve_scaling_flags(const ScalingFlags& flags) {
  using scaling::Form;
  check_flag(flags.K1, "--K1", false);
  check_flag(flags.K2, "--K2", false);
  check_flag(flags.H1, "--H1", false);
  check_flag(flags.H2, "--H2", false);
  check_flag(flags.mu, "--mu", false);
  check_flag(flags.nu, "--nu", true);
  check_flag(flags.gravity, "--gravity", true);
  check_flag(flags.target_density, "--target-density", false);
  check_flag(flags.impactor_density, "--impactor-density", false);
  check_flag(flags.velocity, "--velocity", false);
  check_flag(flags.strength, "--strength", true);
  if (flags.mu && *flags.mu > 1.0) {
    throw InputError("--mu " + format_number(*flags.mu) +
                     " is not allowed: must be in (0, 1] (1/3 .. 2/3 expected)");
  }

  const bool k_given = flags.K1 || flags.K2;
  const bool h_given = flags.H1 || flags.H2;
  if (k_given && h_given) {
    throw InputError(
        "--K1/--K2 (Holsapple form) and --H1/--H2 (Housen & Holsapple 2011 form) cannot be mixed: give one "
        "pair");
  }
  if (flags.params && flags.fit_file) {
    throw InputError("--params " + *flags.params + " and --fit " + *flags.fit_file +
                     " cannot both be given: choose one base law");
  }
  if (flags.group && !flags.fit_file) {
    throw InputError("--group " + *flags.group +
                     " is not allowed without --fit: it chooses a group of a grouped fit");
  }

  ScalingInputs out;
  bool have_base = false;
  if (flags.params) {
    const auto set = scaling::load_constant_set(*flags.params);
    out.law = set.law;
    out.law_source = "set " + set.name;
    out.strength = set.strength;
    out.target_density = set.target_density;
    have_base = true;
  } else if (flags.fit_file) {
    scaling::FittedLaw fitted;
    try {
      fitted = scaling::load_fitted_law(*flags.fit_file, flags.group);
    } catch (const InputError& e) {
      // The library speaks of a group selector; on the command line that is --group.
      const std::string what = e.what();
      if (what.find("group selector") == std::string::npos) throw;
      throw InputError((flags.group ? "--group " + *flags.group + ": " : std::string("--fit: ")) + what +
                       (flags.group ? "" : " (give it with --group)"));
    }
    out.law = fitted.law;
    out.law_source = "fit " + *flags.fit_file;
    if (!fitted.group.empty()) out.law_source += " group " + scaling::describe(fitted.group);
    out.group = fitted.group;
    out.strength = fitted.strength;
    out.covariance = fitted.covariance;
    have_base = true;
  } else {
    out.law_source = "flags";
  }

  const Form wanted = k_given ? Form::holsapple : h_given ? Form::hh2011 : out.law.form;
  if (have_base && wanted != out.law.form) {
    if (std::isnan(out.law.coefficient_1) || std::isnan(out.law.coefficient_2)) {
      throw InputError(out.law_source +
                       " does not give both coefficients, so it cannot be converted to the " +
                       scaling::to_string(wanted) + " form that " + (k_given ? "--K1/--K2" : "--H1/--H2") +
                       " select; use the set's own form (" + scaling::to_string(out.law.form) + ")");
    }
    out.law = scaling::convert(out.law, wanted);
  }
  out.law.form = wanted;
  const std::optional<double>& c1 = wanted == Form::holsapple ? flags.K1 : flags.H1;
  const std::optional<double>& c2 = wanted == Form::holsapple ? flags.K2 : flags.H2;
  const std::string prefix = wanted == Form::holsapple ? "--K" : "--H";
  if (c1) out.law.coefficient_1 = *c1;
  if (c2) out.law.coefficient_2 = *c2;
  if (flags.mu) out.law.mu = *flags.mu;
  if (flags.nu) out.law.nu = *flags.nu;
  if (out.covariance.has_covariance() && (k_given || h_given || flags.mu || flags.nu)) {
    out.covariance = scaling::LawCovariance{};
    out.covariance_note =
        "the fit's covariance is not propagated: a constant flag (--K1, --K2, --H1, --H2, --mu, "
        "--nu) overrides the fitted law";
  }
  out.covariance.law = out.law;
  if (!have_base) {
    if (!k_given && !h_given) {
      throw InputError(
          "no scaling law given: use --params NAME, --fit FIT.json, or --K1 --K2 (or --H1 --H2) "
          "with --mu and --nu");
    }
    if (!c1) throw InputError(prefix + "1 is required with " + prefix + "2 (no --params or --fit given)");
    if (!c2) throw InputError(prefix + "2 is required with " + prefix + "1 (no --params or --fit given)");
    if (!flags.mu) throw InputError("--mu is required (no --params or --fit given)");
    if (!flags.nu) throw InputError("--nu is required (no --params or --fit given)");
  }
  if (flags.strength) out.strength = flags.strength;
  if (flags.target_density) out.target_density = flags.target_density;
  out.gravity = flags.gravity;
  out.impactor_density = flags.impactor_density;
  out.velocity = flags.velocity;
  return out;
}

nlohmann::json scaling_law_json(const ScalingInputs& inputs) {
  nlohmann::json out{{"source", inputs.law_source},
                     {"form", scaling::to_string(inputs.law.form)},
                     {"coefficient_1", inputs.law.coefficient_1},
                     {"coefficient_2", inputs.law.coefficient_2},
                     {"mu", inputs.law.mu},
                     {"nu", inputs.law.nu}};
  if (!inputs.group.empty()) {
    nlohmann::json group = nlohmann::json::object();
    for (const auto& [column, value] : inputs.group) group[column] = value;
    out["group"] = group;
  }
  return out;
}

}  // namespace craterkit::cli
