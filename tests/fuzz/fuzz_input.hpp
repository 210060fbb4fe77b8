#pragma once
// What the fuzz targets share: the readers under test take files, so each input is written to
// a file in one scratch directory per process (the tests' TemporaryDirectory, removed at exit).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "tests/support/temporary_directory.hpp"

namespace cocopp::fuzz {

/// `data` written to `name` in this process's scratch directory; returns its path.
inline std::filesystem::path write_input(const std::string& name, const std::uint8_t* data,
                                         std::size_t size) {
  static const testing::TemporaryDirectory directory;
  const auto file = directory / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + file.string());
  return file;
}

}  // namespace cocopp::fuzz
