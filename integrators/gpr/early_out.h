// Early out of gradient-domain path reusing (Bauszat et al. 2017, Sec. 3.3: "an early out
// for connection attempts which are guaranteed to add no contribution, i.e. base paths
// with zero contribution after the connection vertex"). The base walk is stored whole, so
// before it is shifted to the tile we know which of its vertices can still carry light.
//
// A vertex x_j is dark when no direction of arrival can make it or its light sample
// contribute: it is no emitter (a surface vertex without an emitter; an environment
// vertex of zero emission -- it is reached along the base's own direction) and its light
// sample is not live (live: valid, density > 0, visible from x_j, radiance > 0; all of
// these are properties of the shared points, not of the arriving direction).
//
// Cut point a (2 <= a < n): x_{a-1} is connectable and left by a non-delta lobe, x_a is
// connectable, and every x_j, j >= a, is dark. Then every successful reuse of the walk
// reaches x_a by reconnection (or shares it already: the reuse shift has matching
// classes, pr_tracer.h), so each concrete path through x_a or beyond has the value 0 in
// every pixel, and the concrete paths ending before x_a are shifted exactly as from the
// whole walk (their shift never looks at x_a). Truncating the walk to x_0..x_{a-1}
// therefore changes no estimate and no MIS weight of a path that can carry light; it
// saves the reconnection ray and everything behind it, for every pixel of the tile.
#pragma once

#include "pathspace/path.h"

namespace dp::integrators {

// The number of leading vertices of `base` worth shifting: the smallest cut point a, or
// base.size() if there is none.
int live_prefix(const pathspace::Path& base);

// False if no concrete path of the walk x_0..x_{n-1} (n = base.size()) with >= 2 segments
// can carry light in any pixel of the tile: n <= 1, or n == 2 (after the cut) and the
// light sample at x_1 is not live. Such a base is not shifted at all.
bool can_contribute(const pathspace::Path& base);

}  // namespace dp::integrators
