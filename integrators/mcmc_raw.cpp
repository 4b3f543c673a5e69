#include "integrators/mcmc_raw.h"

namespace dp::integrators {

namespace {
// Six double slots: pixel 0 = (b.sum, b.n, mutations), pixel 1 = (factor.sum, factor.n,
// 0) -- of a second buffer on a 1-pixel image. Counts as doubles: exact below 2^53.
constexpr const char* kNorm = "mcmc.norm";
constexpr const char* kNorm1 = "mcmc.norm.1";
}  // namespace

double McmcNorm::value() const {
  if (b.n <= 0) return 0.0;
  const double mean = b.sum / double(b.n);
  return factor.n > 0 ? mean * (factor.sum / double(factor.n)) : mean;
}

double McmcNorm::scale(int64_t pixels) const {
  return mutations > 0 ? value() * double(pixels) / double(mutations) : 0.0;
}

void McmcNorm::write(core::RawImage& raw) const {
  const size_t n = raw.pixels();
  std::vector<Rgbd> slots(n, Rgbd::Zero());
  slots[0] = Rgbd(b.sum, double(b.n), double(mutations));
  const Rgbd second(factor.sum, double(factor.n), 0.0);
  if (n >= 2) {
    slots[1] = second;
  } else {
    std::vector<Rgbd> more(n, Rgbd::Zero());
    more[0] = second;
    raw.sums[kNorm1] = std::move(more);
  }
  raw.sums[kNorm] = std::move(slots);
}

McmcNorm McmcNorm::read(const core::RawImage& raw) {
  const std::vector<Rgbd>& slots = raw.sum(kNorm);
  const Rgbd first = slots[0], second = slots.size() >= 2 ? slots[1] : raw.sum(kNorm1)[0];
  McmcNorm m;
  m.b.sum = first[0];
  m.b.n = int64_t(first[1]);
  m.mutations = int64_t(first[2]);
  m.factor.sum = second[0];
  m.factor.n = int64_t(second[1]);
  return m;
}

core::RawImage empty_raw(int width, int height) {
  core::RawImage raw;
  raw.width = width;
  raw.height = height;
  return raw;
}

void fill_mcmc_counts(const McmcNorm& norm, int64_t pixels, const RenderOptions& options, RenderResult& result) {
  result.min_spp = result.max_spp = norm.mutations / pixels;
  result.partial = options.spp > 0 && norm.mutations < int64_t(options.spp) * pixels;
  result.info["b"] = norm.value();
  result.info["mutations_per_pixel"] = double(norm.mutations) / double(pixels);
}

void fill_part_counts(int64_t mutations, int64_t pixels, RenderResult& result) {
  result.min_spp = mutations / pixels;
  result.max_spp = (mutations + pixels - 1) / pixels;
}

RenderOptions finish_options(const RenderOptions& options) {
  RenderOptions o = options;
  if (options.time_budget > 0) o.spp = 0;
  return o;
}

}  // namespace dp::integrators
