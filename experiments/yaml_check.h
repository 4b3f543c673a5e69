// Typed, line-aware access to yaml-cpp nodes for experiment files. Every failure throws
// dp::ParseError (structure: unknown/missing keys, wrong types) or dp::ValueError (a
// value out of range) whose what() is "experiment-file:line: problem", the line taken
// from the node's YAML::Mark (1-based). Internal to experiments/.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace dp::experiments::yamlx {

struct Ctx {
  std::string file;                // the experiment file as given (for messages)
  std::filesystem::path base_dir;  // relative paths resolve against this folder
};

// 1-based line of a node, 0 if unknown.
int line_of(const YAML::Node& node);
[[noreturn]] void parse_error(const Ctx& ctx, const YAML::Node& at, const std::string& message);
[[noreturn]] void value_error(const Ctx& ctx, const YAML::Node& at, const std::string& message);

// ParseError unless `node` is a map whose keys are all in `allowed` (reported at the
// offending key's line), each at most once.
void check_keys(const Ctx& ctx, const YAML::Node& node, const std::vector<std::string>& allowed,
                const std::string& what);
// The value of a required key (ParseError at the map's line when absent).
YAML::Node require(const Ctx& ctx, const YAML::Node& map, const std::string& key, const std::string& what);

std::string get_string(const Ctx& ctx, const YAML::Node& node, const std::string& name);
// Finite number (ValueError for .inf/.nan), integer (ParseError for "3.5").
double get_number(const Ctx& ctx, const YAML::Node& node, const std::string& name);
long long get_integer(const Ctx& ctx, const YAML::Node& node, const std::string& name);
// A list; a single scalar is accepted as a list of one when `allow_scalar`.
std::vector<YAML::Node> get_list(const Ctx& ctx, const YAML::Node& node, const std::string& name,
                                 bool allow_scalar = false);

// `relative` resolved against ctx.base_dir unless absolute.
std::string resolve_path(const Ctx& ctx, const std::string& relative);

}  // namespace dp::experiments::yamlx
