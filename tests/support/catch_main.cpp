// SPDX-License-Identifier: MIT
// Catch2 main for every test executable: contract violations throw so REQUIRE_THROWS sees them.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <support/contract_violation.hpp>

int main(int argc, char* argv[]) {
  curvestep::contract_handler = [](const char* condition, const char* file, int line) {
    throw curvestep::testing::ContractViolation(condition, file, line);
  };
  return Catch::Session().run(argc, argv);
}
