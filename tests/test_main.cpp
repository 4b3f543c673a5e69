// The one Catch2 main for all test executables (compiled once).
// Catch2 v2's command line accepts `--warn` only once ("Unrecognised token: --warn" on a
// second one, although its handler ORs the flags), so this main takes every `--warn X`
// / `-w X` itself and ORs them into the configuration: dp_add_test passes
// `--warn NoTests --warn NoAssertions` (a test case without an assertion fails).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <string>
#include <vector>

int main(int argc, char* argv[]) {
  std::vector<char*> args;
  std::vector<std::string> warnings;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--warn" || a == "-w") && i + 1 < argc) {
      warnings.emplace_back(argv[++i]);
      continue;
    }
    args.push_back(argv[i]);
  }
  Catch::Session session;
  if (const int rc = session.applyCommandLine(int(args.size()), args.data())) return rc;
  if (session.configData().showHelp || session.configData().libIdentify) return 0;
  for (const std::string& w : warnings) {
    // Catch validates the name (an unknown warning is an input error, as with one --warn).
    const char* one[] = {argv[0], "--warn", w.c_str()};
    if (const int rc = session.applyCommandLine(3, one)) return rc;
  }
  return session.run();
}
