#include "experiments/results_csv.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace dp::experiments {

namespace {
std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}
}  // namespace

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string results_csv_text(const ExperimentConfig& config, const std::vector<PointResult>& points) {
  std::string out = "name,budget,seed,wall_time,spp";
  for (const auto& m : config.metrics) out += "," + csv_field(m.column());
  out += "\n";
  for (const auto& p : points) {
    out += csv_field(config.runs.at(p.run).name) + "," + number(config.budgets.at(p.budget)) + "," +
           std::to_string(p.seed) + "," + number(p.wall_time) + "," + std::to_string(p.spp);
    for (double v : p.metrics) out += "," + number(v);
    out += "\n";
  }
  return out;
}

void write_results_csv(const std::string& path, const ExperimentConfig& config, const std::vector<PointResult>& points) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw IoError("cannot write", tmp);
    f << results_csv_text(config, points);
    if (!f) throw IoError("write failed", tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace dp::experiments
