#include "craterkit/sph/io/step_csv_log.hpp"

#include <sstream>
#include <stdexcept>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {

namespace {

std::vector<std::string> split_columns(const std::string& line) {
  std::vector<std::string> columns;
  std::string column;
  std::istringstream in(line);
  while (std::getline(in, column, ',')) columns.push_back(column);
  if (!line.empty() && line.back() == ',') columns.emplace_back();
  return columns;
}

bool parse_step(const std::string& text, std::uint64_t* value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  try {
    *value = std::stoull(text);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

}  // namespace

StepCsvLog::StepCsvLog(std::filesystem::path csv, std::string header, std::size_t step_column,
                       std::int64_t restart_step, std::optional<std::uint64_t> expected_rows)
    : path_(std::move(csv)) {
  std::error_code ec;
  const std::string recovery =
      "the log cannot be rebuilt from the checkpoint: restore the file, or start the run anew";
  if (restart_step >= 0 && expected_rows && !std::filesystem::exists(path_, ec)) {
    throw InputError(path_.string() + ": missing; the checkpoint of step " + std::to_string(restart_step) +
                     " was written when it held " + std::to_string(*expected_rows) + " rows; " + recovery);
  }
  if (restart_step >= 0 && std::filesystem::exists(path_, ec)) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path_.string() + " to resume it");
    std::string line;
    if (!std::getline(in, line) || line != header) {
      throw InputError(path_.string() + ": the header is not '" + header +
                       "', so it was not written by this version of craterkit; move it away to start anew");
    }
    const std::size_t n_columns = split_columns(header).size();
    std::string kept = line + '\n';
    std::size_t row = 1;
    while (std::getline(in, line)) {
      ++row;
      if (in.eof()) break;  // an incomplete last line of a killed run
      auto columns = split_columns(line);
      std::uint64_t step = 0;
      if (columns.size() != n_columns || !parse_step(columns[step_column], &step)) {
        throw InputError(path_.string() + " row " + std::to_string(row) + ": '" + line +
                         "' is not a row of " + std::to_string(n_columns) + " columns with an integer step");
      }
      if (step > static_cast<std::uint64_t>(restart_step)) break;  // rows are in step order
      kept += line + '\n';
      kept_.push_back(std::move(columns));
    }
    in.close();
    if (expected_rows && kept_.size() != *expected_rows) {
      throw InputError(path_.string() + ": holds " + std::to_string(kept_.size()) + " rows up to step " +
                       std::to_string(restart_step) +
                       ", but the checkpoint of that step was written when it held " +
                       std::to_string(*expected_rows) + " (truncated or edited); " + recovery);
    }
    rows_ = kept_.size();
    write_text_atomically(path_, kept);
    out_.open(path_, std::ios::binary | std::ios::app);
  } else {
    out_.open(path_, std::ios::binary | std::ios::trunc);
    out_ << header << '\n';
    out_.flush();
  }
  if (!out_) throw std::runtime_error("cannot open " + path_.string() + " for writing");
}

void StepCsvLog::append(const std::string& row) {
  out_ << row << '\n';
  out_.flush();
  ++rows_;
  if (!out_) throw std::runtime_error("cannot write to " + path_.string());
}

}  // namespace craterkit::sph
