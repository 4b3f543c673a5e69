#include "experiments/results_csv.h"

#include <cstdio>
#include "core/atomic_write.h"
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
  core::write_file_atomically(path, results_csv_text(config, points));
}

}  // namespace dp::experiments
