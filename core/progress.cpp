#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace dp::core {

Progress::Progress(std::string label, int64_t total, bool quiet)
    : m_label(std::move(label)), m_total(total > 0 ? total : 1),
      m_enabled(!quiet && isatty(STDERR_FILENO)), m_start(std::chrono::steady_clock::now()),
      m_last_draw(m_start) {}

Progress::~Progress() { finish(); }

void Progress::advance(int64_t n) {
  const int64_t done = m_done.fetch_add(n) + n;
  if (!m_enabled) return;
  draw(double(done) / double(m_total));
}

void Progress::set_fraction(double f) {
  if (m_enabled) draw(f);
}

void Progress::draw(double fraction) {
  std::lock_guard<std::mutex> lock(m_mutex);
  const auto now = std::chrono::steady_clock::now();
  if (m_finished) return;
  if (fraction < 1.0 && now - m_last_draw < std::chrono::milliseconds(200)) return;
  m_last_draw = now;
  fraction = fraction < 0 ? 0 : (fraction > 1 ? 1 : fraction);
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const int width = 30;
  const int filled = int(fraction * width);
  std::string bar(size_t(filled), '=');
  bar.resize(size_t(width), ' ');
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, ETA %.1fs   ", m_label.c_str(), bar.c_str(),
               100.0 * fraction, elapsed, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(m_mutex);
  if (m_finished) return;
  m_finished = true;
  if (m_enabled) std::fprintf(stderr, "\n");
}

}  // namespace dp::core
