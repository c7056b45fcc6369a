// fuzz_expression.cpp — libFuzzer target: arbitrary bytes to cdyn::fuzz::expression_input
// (entries.hpp says what is expected and what is a finding).  scripts/fuzz.sh builds
// and runs it.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cdyn::fuzz::expression_input(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
