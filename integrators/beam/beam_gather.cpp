#include "integrators/beam/beam_gather.h"

#include <algorithm>
#include <cmath>

#include "integrators/media_photons/volume_kernel.h"
#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

Rgb beam_point_weight(const scene::HomogeneousMedium& med, float v, BeamFault fault) {
  const Rgb tr = scene::transmittance(med, v);
  if (fault == BeamFault::no_pass_probability) return tr;
  const float pass = scene::free_flight_pass_probability(med, v);
  return pass > 0.0f ? Rgb(tr / pass) : Rgb(Rgb::Zero());
}

float beam_piece_length(const scene::Scene& scene, const std::vector<MediumBeam>& beams, float r) {
  // Pieces of at most max(16 r, diag / 128) (beam_bvh.h), longer if that would make more
  // than 8M pieces (memory: ~15 bytes a piece with the nodes). On cornell_smoke (128^2,
  // 1 spp, 1 thread) 16 r with 16 pieces a leaf took 0.85x the time and 1/3 of the
  // memory of 8 r with 4 a leaf; 4 r, 32 r and 64 r were slower (the query's cost is
  // the nodes and pieces near the camera ray, ~1000 node visits for ~65 candidates).
  double total = 0.0;
  for (const MediumBeam& b : beams) total += double(b.length);
  const double diag = double(scene.bounds().diagonal());
  return float(std::max({16.0 * double(r), (std::isfinite(diag) ? diag : 0.0) / 128.0, total / 8e6}));
}

namespace {

// int_{t0}^{t1} Tr_c(t) dt per channel (closed form of the homogeneous medium).
Rgbd beam_camera_tr_integral(const scene::HomogeneousMedium& med, double t0, double t1) {
  const Rgb st = med.sigma_t();
  Rgbd out;
  for (int ch = 0; ch < 3; ++ch) {
    const double sig = double(st[ch]);
    out[ch] = sig > 0.0 ? std::exp(-sig * t0) * -std::expm1(-sig * (t1 - t0)) / sig : t1 - t0;
  }
  return out;
}

// The beam's throughput times its point weight Tr_b(v) / P(v) (1 in a grid medium: see the
// header) times sigma_s at the point (grid media: scaled by the density there).
Rgb beam_point_value(const scene::HomogeneousMedium& med, const MediumBeam& beam, double v, BeamFault fault) {
  if (!med.heterogeneous()) return beam.beta * beam_point_weight(med, float(v), fault) * med.sigma_s;
  return beam.beta * med.sigma_s * med.density->lookup(beam.a + float(v) * beam.w);
}

}  // namespace

bool beam_tube_interval(const Vec3& a, const Vec3& w, double v0, double v1, const Vec3& c, const Vec3& w_c, double s,
                        double r, double& lo, double& hi) {
  using V = Eigen::Vector3d;
  const V wc = w_c.cast<double>(), wb = w.cast<double>();
  const V q = (a - c).cast<double>();  // the beam's start relative to the camera origin
  const double r2 = r * r;
  const double cos_t = wb.dot(wc), qt = q.dot(wc);
  // v where b(v) is within r of the camera line: |q_perp + v wb_perp|^2 <= r^2.
  const V qp = q - qt * wc, wbp = wb - cos_t * wc;
  const double A = wbp.squaredNorm(), B = qp.dot(wbp);
  lo = v0;
  hi = v1;
  if (A > 1e-12) {
    const double vc = -B / A;
    const double dmin2 = (qp + vc * wbp).squaredNorm();
    if (dmin2 > r2) return false;
    const double hw = std::sqrt((r2 - dmin2) / A);
    lo = std::max(lo, vc - hw);
    hi = std::min(hi, vc + hw);
  } else if (qp.squaredNorm() > r2) {
    return false;  // parallel, farther than r
  }
  // ... and whose projection t(v) = qt + v cos lies in [-r, s + r].
  if (std::abs(cos_t) > 1e-12) {
    const double va = (-r - qt) / cos_t, vb = (s + r - qt) / cos_t;
    lo = std::max(lo, std::min(va, vb));
    hi = std::min(hi, std::max(va, vb));
  } else if (qt < -r || qt > s + r) {
    return false;
  }
  return hi > lo;
}

Rgb beam_beam_3d(const scene::HomogeneousMedium& med, const MediumBeam& beam, float v0, float v1, const Vec3& c,
                 const Vec3& w_c, float s, float r, float u, BeamFault fault,
                 const scene::TransmittanceProfile* camera_tr) {
  using V = Eigen::Vector3d;
  const V wc = w_c.cast<double>(), wb = beam.w.cast<double>();
  const V q = (beam.a - c).cast<double>();
  const double rr = double(r), r2 = rr * rr, S = double(s);
  double lo = 0, hi = 0;
  if (!beam_tube_interval(beam.a, beam.w, double(v0), double(v1), c, w_c, S, rr, lo, hi)) return Rgb::Zero();
  const double chord = hi - lo;
  if (!(chord > 0.0)) return Rgb::Zero();
  const double v = lo + double(u) * chord;
  // The camera chord within r of b(v), clipped to the segment.
  const V p = q + v * wb;
  const double tp = p.dot(wc), d2 = std::max(0.0, p.squaredNorm() - tp * tp);
  if (d2 > r2) return Rgb::Zero();
  const double h = std::sqrt(r2 - d2);
  const double t0 = std::max(0.0, tp - h), t1 = std::min(S, tp + h);
  if (!(t1 > t0)) return Rgb::Zero();
  const Rgbd tr_c = fault == BeamFault::no_camera_transmittance ? Rgbd(Rgbd::Constant(t1 - t0))
                    : camera_tr ? Rgbd(Rgbd::Constant(double(camera_tr->integral(float(t0), float(t1)))))
                                : beam_camera_tr_integral(med, t0, t1);
  const double inv_pdf = fault == BeamFault::no_chord_pdf ? 1.0 : chord;
  const float rho = scene::HenyeyGreenstein(med.phase).eval(beam.w, -w_c);
  const Rgbd w = beam_point_value(med, beam, v, fault).cast<double>();
  return (w * tr_c * (double(rho) * uniform_kernel(3, rr) * inv_pdf)).cast<float>();
}

Rgb beam_beam_1d(const scene::HomogeneousMedium& med, const MediumBeam& beam, float v0, float v1, const Vec3& c,
                 const Vec3& w_c, float s, float r, GatherCounters& counters, BeamFault fault,
                 const scene::TransmittanceProfile* camera_tr) {
  using V = Eigen::Vector3d;
  const V wc = w_c.cast<double>(), wb = beam.w.cast<double>();
  const V w = (beam.a - c).cast<double>();
  const double cos_t = wb.dot(wc), sin2 = 1.0 - cos_t * cos_t;
  if (!(sin2 > 1e-12)) {
    ++counters.parallel;
    return Rgb::Zero();
  }
  // Closest points of the lines c + t w_c and a + v w_b: t = d1 + v cos, v = t cos - d2.
  const double d1 = wc.dot(w), d2 = wb.dot(w);
  const double t = (d1 - cos_t * d2) / sin2, v = (cos_t * d1 - d2) / sin2;
  // The closest point on the camera segment and in this piece of the beam ([v0, v1), the
  // last piece closed: each closest point belongs to exactly one piece).
  const bool last = !(v1 < beam.length);
  if (!(t >= 0.0 && t <= double(s) && v >= double(v0) && (v < double(v1) || (last && v <= double(v1)))))
    return Rgb::Zero();
  const double u2 = (w + v * wb - t * wc).squaredNorm();
  if (u2 > double(r) * double(r)) return Rgb::Zero();
  const float rho = scene::HenyeyGreenstein(med.phase).eval(beam.w, -w_c);
  const Rgb tr_c = fault == BeamFault::no_camera_transmittance ? Rgb(Rgb::Ones())
                   : camera_tr ? Rgb(Rgb::Constant(camera_tr->at(float(t))))
                               : scene::transmittance(med, float(t));
  const double k1 = 1.0 / (2.0 * double(r));
  const double jac = fault == BeamFault::no_sin_theta ? 1.0 : 1.0 / std::sqrt(sin2);
  const Rgb wgt = beam_point_value(med, beam, v, fault) * tr_c;
  return (wgt.cast<double>() * (double(rho) * k1 * jac)).cast<float>();
}

Rgb BeamGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                       GatherCounters& counters) const {
  if (max_photon_depth < 1 || m_beams.empty() || !(seg_len > 0.0f)) return Rgb::Zero();
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  if (is_black(med.sigma_s)) {
    ++counters.empty_segments;
    return Rgb::Zero();
  }
  // An unbounded segment ends where it leaves the beams' bounds (+ margin): none beyond.
  const float s = m_beams.clip(ray.o, ray.d, seg_len, m_radius);
  ++counters.queries;
  if (!(s > 0.0f)) return Rgb::Zero();
  const bool k3 = m_settings.kernel == BeamKernel::k3d;
  // A grid medium: the camera side's Tr from one ratio-tracking profile of the segment.
  thread_local scene::TransmittanceProfile profile;
  const scene::TransmittanceProfile* camera_tr = nullptr;
  if (med.heterogeneous()) {
    profile.track(med, ray.o, ray.d, s, rng);
    camera_tr = &profile;
  }
  Rgbd sum = Rgbd::Zero();
  m_beams.query_segment(
      ray.o, ray.d, s, m_radius,
      [&](const MediumBeam& b, float v0, float v1) {
        if (b.medium != medium) return;
        if (b.depth > max_photon_depth) {
          ++counters.depth_skipped;
          return;
        }
        ++counters.candidates;
        const Rgb v = k3 ? beam_beam_3d(med, b, v0, v1, ray.o, ray.d, s, m_radius, rng.uniform(), m_settings.fault,
                                        camera_tr)
                         : beam_beam_1d(med, b, v0, v1, ray.o, ray.d, s, m_radius, counters, m_settings.fault, camera_tr);
        if (is_black(v)) return;
        ++counters.photons;
        sum += v.cast<double>();
      },
      m_settings.fault != BeamFault::bvh_unpadded);
  return (sum / double(m_paths)).cast<float>();
}

}  // namespace dp::integrators
