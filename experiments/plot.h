// Convergence plots are drawn by experiments/plot_convergence.py (matplotlib); the C++
// side only runs it. The script is found at $DP_PLOT_SCRIPT, else in the source tree's
// experiments/ folder (compiled in).
#pragma once

#include <string>

namespace dp::experiments {

std::string plot_script_path();
// The first of $DP_PYTHON, python3, /usr/bin/python3 that can import matplotlib; "" if none.
std::string find_python();
// Runs `<find_python()> plot_convergence.py CSV --out PREFIX --title TITLE` and returns
// PREFIX.png, or "" after a warning when python3 with matplotlib or the script is missing
// or the script fails.
std::string make_convergence_plot(const std::string& csv, const std::string& out_prefix, const std::string& title);
// 'text' quoted for /bin/sh.
std::string shell_quote(const std::string& text);

}  // namespace dp::experiments
