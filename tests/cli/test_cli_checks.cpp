// The CLI's numeric option checks (apps/cli_checks.h, issue 18): each extreme value is a
// CLI11 usage error (one line naming the option), each ordinary value passes. The
// end-to-end run of the same inputs through `deltapath render` is in test_cli.sh.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "apps/cli_checks.h"

namespace {

// Parses `--name value` against an option carrying `check`; true if CLI11 accepts it.
template <typename T>
bool accepts(const CLI::Validator& check, const std::string& value) {
  CLI::App app;
  T v{};
  app.add_option("--x", v)->check(check);
  std::vector<std::string> args = {value, "--x"};  // CLI11 parses the vector back to front
  try {
    app.parse(args);
  } catch (const CLI::ParseError&) {
    return false;
  }
  return true;
}

}  // namespace

TEST_CASE("cli: --spp, --max-depth, --time and --threads reject extreme values", "[unit]") {
  using dp::apps::path_depth;
  using dp::apps::sample_count;
  using dp::apps::seconds;
  using dp::apps::thread_count;
  for (const char* bad : {"0", "-1", "2000000000"}) CHECK_FALSE(accepts<int>(sample_count(), bad));
  for (const char* ok : {"1", "64"}) CHECK(accepts<int>(sample_count(), ok));
  for (const char* bad : {"0", "-1", "100000"}) CHECK_FALSE(accepts<int>(path_depth(), bad));
  CHECK(accepts<int>(path_depth(), "8"));
  for (const char* bad : {"inf", "nan", "-3", "0", "1e300", "1e400", "0x10", "5s", ""}) CHECK_FALSE(accepts<double>(seconds(), bad));
  for (const char* ok : {"1e-9", "2.5", "60"}) CHECK(accepts<double>(seconds(), ok));
  for (const char* bad : {"100000", "-1", "1025"}) CHECK_FALSE(accepts<int>(thread_count(), bad));
  for (const char* ok : {"0", "1", "1024"}) CHECK(accepts<int>(thread_count(), ok));
}

TEST_CASE("cli: --part accepts K/N with 1 <= K <= N only", "[unit]") {
  for (const char* ok : {"1/1", "1/3", "3/3", "07/8"}) CHECK(accepts<std::string>(dp::apps::part_spec(), ok));
  for (const char* bad : {"0/3", "4/3", "3", "/3", "1/", "1/0", "-1/3", "1/-3", "a/b", "1/2/3", "1 /2", "1/2097152",
                          "999999999/999999999", ""})
    CHECK_FALSE(accepts<std::string>(dp::apps::part_spec(), bad));
  int k = 0, n = 0;
  REQUIRE(dp::apps::parse_part("2/5", k, n));
  CHECK((k == 2 && n == 5));
}
