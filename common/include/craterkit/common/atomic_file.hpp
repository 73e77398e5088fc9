#pragma once
// Atomic output: content is written to a temporary file beside the target and renamed over it only
// once complete, so a killed run never leaves a truncated file under the final name.
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "craterkit/common/input_error.hpp"

namespace craterkit {

// Temporary name in the same directory (rename is atomic only within one file system).
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  auto name = target.filename().string();
  return target.parent_path() / ("." + name + ".tmp." + std::to_string(::getpid()));
}

// Calls write(tmp_path) to produce the file, then renames it to target. On any exception the
// temporary file is removed and the exception propagates (a failure to write, e.g. a full disk, as a
// std::runtime_error "cannot write <target>: ..." naming the file the user asked for); target is untouched.
inline void write_atomically(const std::filesystem::path& target,
                             const std::function<void(const std::filesystem::path&)>& write) {
  const auto tmp = temporary_sibling(target);
  auto remove_tmp = [&] {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
  };
  try {
    write(tmp);
    std::filesystem::rename(tmp, target);
  } catch (const InputError&) {
    remove_tmp();
    throw;
  } catch (const std::filesystem::filesystem_error& e) {
    remove_tmp();
    throw std::runtime_error("cannot write " + target.string() + ": " + e.code().message());
  } catch (const std::runtime_error& e) {
    remove_tmp();
    if (std::string_view(e.what()).find(target.string()) != std::string_view::npos) throw;
    throw std::runtime_error("cannot write " + target.string() + ": " + e.what());
  } catch (...) {
    remove_tmp();
    throw;
  }
}

inline void write_text_atomically(const std::filesystem::path& target, std::string_view text) {
  write_atomically(target, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot create a file in " + tmp.parent_path().string());
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) throw std::runtime_error("writing failed (disk full?)");
  });
}

}  // namespace craterkit
