// A camera path (random walk with next-event estimation) as data.
// Convention: the CAMERA END COMES FIRST. vertices[0] = x_0 is the camera, x_k is reached
// after k segments; a surface hit seen directly from the camera is x_1 (a directly
// visible emitter is a path of depth 1, as in the reference path tracer). nee[k] is the
// light sample drawn at x_k (nee[0] unused). One walk stands for a family of concrete
// paths: for every k >= 1, the NEE path (x_0..x_k, nee[k]) and the BSDF path
// (x_0..x_k, x_{k+1}) whose last vertex may or may not emit.
// raster is the continuous image position of the primary ray; pixel = floor(raster).
#pragma once

#include <vector>

#include "pathspace/vertex.h"

namespace dp::pathspace {

struct Path {
  Vec2 raster{0, 0};
  std::vector<Vertex> vertices;
  std::vector<LightSample> nee;  // same size as vertices

  int size() const { return int(vertices.size()); }
  const Vertex& operator[](int k) const { return vertices[size_t(k)]; }
  Vertex& operator[](int k) { return vertices[size_t(k)]; }
  void clear() {
    vertices.clear();
    nee.clear();
  }
  Vertex& append(const Vertex& v) {
    vertices.push_back(v);
    nee.emplace_back();
    return vertices.back();
  }
};

}  // namespace dp::pathspace
