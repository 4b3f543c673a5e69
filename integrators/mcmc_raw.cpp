#include "integrators/mcmc_raw.h"

namespace dp::integrators {

namespace {
constexpr const char* kB = "mcmc.b";
constexpr const char* kBSamples = "mcmc.b_samples";
constexpr const char* kFactorSamples = "mcmc.factor_samples";
constexpr const char* kMutations = "mcmc.mutations";
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
  std::vector<Rgbd> sums(n, Rgbd::Zero());
  sums[0] = Rgbd(b.sum, factor.sum, 0.0);
  raw.sums[kB] = std::move(sums);
  auto scalar = [&](int64_t v) {
    std::vector<int64_t> c(n, 0);
    c[0] = v;
    return c;
  };
  raw.counts[kBSamples] = scalar(b.n);
  raw.counts[kFactorSamples] = scalar(factor.n);
  raw.counts[kMutations] = scalar(mutations);
}

McmcNorm McmcNorm::read(const core::RawImage& raw) {
  McmcNorm m;
  const Rgbd s = raw.sum(kB)[0];
  m.b.sum = s[0];
  m.factor.sum = s[1];
  m.b.n = raw.count(kBSamples)[0];
  m.factor.n = raw.count(kFactorSamples)[0];
  m.mutations = raw.count(kMutations)[0];
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
