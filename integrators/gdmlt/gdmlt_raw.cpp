#include "integrators/gdmlt/gdmlt_raw.h"

#include <algorithm>
#include <string>
#include <type_traits>

#include "core/error.h"
#include "gradients/symmetric_gradient.h"
#include "integrators/direct_pass.h"
#include "integrators/gdmlt/gdmlt_path.h"
#include "integrators/gradient_output.h"
#include "integrators/tile_scheduler.h"
#include "kernels_adaptive/kernel_problem.h"
#include "reconstruct/pair_layers.h"

namespace dp::integrators {

namespace {
std::string rows_name(int k) { return "rows." + std::to_string(k); }

// A feature buffer (kernels_adaptive/features.h, values in [0, 1]) as an image layer.
template <typename T>
core::Image feature_image(const std::vector<T>& v, int w, int h) {
  core::Image img(w, h);
  for (size_t i = 0; i < v.size(); ++i) {
    if constexpr (std::is_same_v<T, float>)
      img[i] = Rgb::Constant(v[i]);
    else
      img[i] = Rgb(float(v[i][0]), float(v[i][1]), float(v[i][2]));
  }
  return img;
}

// A per-pixel buffer stored by one part per pixel (header), as floats; strict: every
// pixel must be there (else 0 where a part is missing).
template <typename T>
std::vector<T> stored(const core::RawImage& raw, const std::string& name, bool strict = true) {
  const std::vector<Rgbd>& sum = raw.sum(name);
  const std::vector<int64_t>& n = raw.count("features.n");
  std::vector<T> out(sum.size());
  for (size_t i = 0; i < sum.size(); ++i) {
    if (n[i] == 0 && strict)
      throw ValueError("gdmlt: the feature buffers of pixel " + std::to_string(i) +
                       " are in a missing part: the adaptive kernel needs every part (merge them all)");
    if (n[i] > 1)
      throw ValueError("gdmlt: pixel " + std::to_string(i) + " of buffer '" + name + "' is stored " +
                       std::to_string(n[i]) + " times, not once");
    if constexpr (std::is_same_v<T, float>)
      out[i] = float(sum[i][0]);
    else
      out[i] = T(float(sum[i][0]), float(sum[i][1]), float(sum[i][2]));
  }
  return out;
}
}  // namespace

kernels_adaptive::PairKernel gdmlt_kernel(const GdmltSettings& settings, const kernels_adaptive::Features& features,
                                          int width, int height) {
  if (settings.kernel != "adaptive") return kernels_adaptive::standard_kernel(width, height);
  kernels_adaptive::PairKernel kernel = kernels_adaptive::adaptive_kernel(features, settings.affinity);
  if (settings.fault_symmetric_as_one)  // tests' negative control only
    for (auto& e : kernel.entries) e.weight = e.weight == 2.0f ? 1.0f : e.weight;
  return kernel;
}

core::RawImage gdmlt_raw(const ChainRunResult& run, const McmcNorm& norm, const kernels_adaptive::Features& features,
                         const gradients::AoMap* ao, const GdmltSettings& settings, const RenderOptions& options,
                         int width, int height) {
  core::RawImage raw = empty_raw(width, height);
  raw.sums["primal"] = run.sums[kGdmltPrimal];
  raw.sums["density"] = run.sums[kGdmltDensity];
  for (size_t k = kGdmltRows; k < run.sums.size(); ++k) raw.sums[rows_name(int(k - kGdmltRows))] = run.sums[k];
  norm.write(raw);
  const size_t n = raw.pixels();
  const bool adaptive = settings.kernel == "adaptive";
  auto mine = [&](size_t i) { return options.parts <= 1 || int(i % size_t(options.parts)) == options.part; };
  if (adaptive) {
    std::vector<Rgbd> normal(n, Rgbd::Zero()), albedo(n, Rgbd::Zero()), depth(n, Rgbd::Zero());
    for (size_t i = 0; i < n; ++i) {
      if (!mine(i)) continue;
      normal[i] = features.normal[i].cast<double>();
      albedo[i] = features.albedo[i].cast<double>();
      depth[i] = Rgbd::Constant(double(features.depth[i]));
    }
    raw.sums["features.normal"] = std::move(normal);
    raw.sums["features.albedo"] = std::move(albedo);
    raw.sums["features.depth"] = std::move(depth);
  }
  if (ao) {
    std::vector<Rgbd> a(n, Rgbd::Zero());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        if (mine(i)) a[i] = Rgbd::Constant(double(std::max(0.0f, ao->at_pixel(x, y))));  // miss: 0
      }
    raw.sums["ao"] = std::move(a);
  }
  if (adaptive || ao) {
    std::vector<int64_t> stored_here(n, 0);
    for (size_t i = 0; i < n; ++i) stored_here[i] = mine(i) ? 1 : 0;
    raw.counts["features.n"] = std::move(stored_here);
  }
  return raw;
}

void add_gdmlt_layers(const core::RawImage& raw, const RenderOptions& options, const GdmltSettings& settings,
                      RenderResult& result) {
  const int w = raw.width, h = raw.height;
  const int64_t pixels = int64_t(w) * int64_t(h);
  const McmcNorm norm = McmcNorm::read(raw);
  const double scale = norm.scale(pixels);
  kernels_adaptive::Features features;
  if (settings.kernel == "adaptive") {
    features.width = w;
    features.height = h;
    features.normal = stored<Vec3>(raw, "features.normal");
    features.albedo = stored<Rgb>(raw, "features.albedo");
    features.depth = stored<float>(raw, "features.depth");
  }
  const kernels_adaptive::PairKernel kernel = gdmlt_kernel(settings, features, w, h);
  const int64_t rows = int64_t(kernel.rows.size());
  auto image_of = [&](const std::vector<Rgbd>& sum, double k) {
    core::Image img(w, h);
    for (size_t i = 0; i < sum.size(); ++i) img[i] = (sum[i] * k).cast<float>();
    return img;
  };
  std::vector<Rgb> row_values(size_t(rows), Rgb::Zero());
  for (int64_t r = 0; r < rows; ++r)
    row_values[size_t(r)] = (raw.sum(rows_name(int(r / pixels)))[size_t(r % pixels)] * scale).cast<float>();
  // Gradient energy (where the sampled gradients put their magnitude; the paper's Fig. 8
  // insets): per pixel, half the summed luminance magnitude of the rows touching it.
  core::Image energy(w, h);
  for (int64_t r = 0; r < rows; ++r) {
    const float e = 0.5f * float(gradients::magnitude(row_values[size_t(r)].cast<double>()));
    const auto& pr = kernel.rows[size_t(r)];
    energy[size_t(pr.i)] += Rgb::Constant(e);
    energy[size_t(pr.j)] += Rgb::Constant(e);
  }
  // Screened Poisson reconstruction of the indirect image (Manzi 2014, Eq. 8), then the
  // direct pass added (Sec. 4). Once, on the summed buffers of all parts.
  const core::Image primal = image_of(raw.sum("primal"), scale);
  const core::Image direct = DirectPass::image(raw);
  if (settings.kernel == "standard") {
    // Rows in forward-difference order (kernels_adaptive::standard_kernel): dx, then dy.
    core::Image dx(w, h), dy(w, h);
    size_t r = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x + 1 < w; ++x) dx(x, y) = row_values[r++];
    for (int y = 0; y + 1 < h; ++y)
      for (int x = 0; x < w; ++x) dy(x, y) = row_values[r++];
    add_gradient_layers(primal, dx, dy, direct, settings.alpha, settings.reconstruction, options, result);
  } else {
    reconstruct::Problem problem = kernels_adaptive::make_problem(kernel, primal, std::move(row_values), settings.alpha);
    if (settings.symmetric_weight != 1.0)
      problem.row_weights = reconstruct::reversed_pair_weights(problem.kernel, float(settings.symmetric_weight));
    add_reconstruction_layers(problem, direct, settings.reconstruction, options, result);
    reconstruct::append_pair_layers(reconstruct::encode_pair_layers(problem.kernel, problem.b), result.layers);
    result.layers.push_back({"features.normal", feature_image(features.normal, w, h)});
    result.layers.push_back({"features.albedo", feature_image(features.albedo, w, h)});
    result.layers.push_back({"features.depth", feature_image(features.depth, w, h)});
  }
  result.layers.push_back({"gradient_energy", std::move(energy)});
  if (raw.sums.count("ao")) result.layers.push_back({"ao", feature_image(stored<float>(raw, "ao", false), w, h)});
  const int64_t mutations = norm.mutations;
  result.layers.push_back(
      {"density", image_of(raw.sum("density"), mutations > 0 ? double(pixels) / double(mutations) : 0.0)});
  fill_mcmc_counts(norm, pixels, options, result);
}

}  // namespace dp::integrators
