#include "integrators/bdpt/bdpt_settings.h"

#include <cstdio>

#include "core/error.h"

namespace dp::integrators {

BdptSettings BdptSettings::read(Settings& s) {
  BdptSettings b;
  b.rr_depth = s.get_int("rr_depth", b.rr_depth, "Russian roulette on each subpath after this many segments");
  const std::string mis = s.get_string("mis", "power", "MIS heuristic over the s/t strategies (Veach 1997, Sec. 9.2)",
                                       {"power", "balance"});
  b.mis.heuristic = mis == "balance" ? pathspace::MisHeuristic::balance : pathspace::MisHeuristic::power;
  const std::string strategy = s.get_string(
      "strategy", "", "render one strategy alone, unweighted: 's,t' (s light vertices, t >= 1 camera vertices; empty = all with MIS)");
  if (!strategy.empty()) {
    int ls = -1, lt = -1;
    char tail = 0;
    if (std::sscanf(strategy.c_str(), "%d,%d%c", &ls, &lt, &tail) != 2 || ls < 0 || lt < 1 || ls + lt < 2)
      throw ValueError("setting 'strategy' must be 's,t' with s >= 0, t >= 1, s + t >= 2 (got '" + strategy + "')", "--set");
    b.only_s = ls;
    b.only_t = lt;
    b.mis.unweighted = true;
  }
  if (b.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return b;
}

}  // namespace dp::integrators
