// SPDX-License-Identifier: Apache-2.0
// Reference for ray / bicubic Bezier patch intersection, in long double: the ground truth of
// the tests and of ppm-bench (library ppm_reference), never linked into libppm.
//
// Deliberately a different algorithm from libppm's (which projects each patch into ray space,
// proves roots with a Krawczyk interval test and runs double-precision Newton on two
// unknowns): here every patch is subdivided with De Casteljau in WORLD space, and a
// sub-patch is dropped when the ray segment misses its control-point box or the slab of its
// control points along the normal of its diagonals (both exact hulls, padded by
// `near_distance`). Subdivision runs down to leaves whose box is below ~1e-6 of the model
// diagonal, and further (to ~1e-9) while the ray is too close to tangent for the leaf to
// hold at most one root (sampled normals n with n.d changing sign or close to it). In each
// leaf a long-double Newton iteration on the three unknowns (u, v, t) of
// S(u, v) - o - t d = 0 gives the root inside the leaf, from the centre and, where the ray
// is near tangent or a normal vanishes, from four more starts. Where no start converges
// inside such a leaf, a damped Gauss-Newton minimisation of the distance between the ray and
// the leaf's surface decides whether the ray touches it at rounding level (kind = singular:
// a real hit, e.g. through a collapsed edge) or passes within `near_distance` (kind =
// tangent, with the distance reported so a caller can decide whether a hit there is
// acceptable). Every root also carries its "dip" (how deep the ray goes through the surface
// before the curvature brings it back), which tells roots that rounding of the input
// cannot remove from those of rays tangent in real arithmetic.
//
// Nothing is shared with libppm: the patches come from a parser of its own, the arithmetic
// is long double throughout (rounding ~1e-19 relative), and the only input from outside is
// the ray. Work per ray is bounded (Options::max_nodes); a ray that hits the bound is
// reported undecided, never answered from a partial search.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace ref {

using real = long double;

struct Patch {
    real p[16][3]; // P[i][j] at index i * 4 + j; S(u, v) = sum_i sum_j B_i(v) B_j(u) P[i][j]
};

// Reads a .bpt file; coordinates are parsed as double (the precision libppm stores) and then
// widened, so both sides intersect the very same surface. Returns false with `error` set.
bool load_bpt(const std::string &path, std::vector<Patch> &patches, std::string &error);

// S(u, v) and, when the pointers are non-null, dS/du and dS/dv.
void evaluate(const Patch &patch, real u, real v, real s[3], real su[3] = nullptr, real sv[3] = nullptr);

enum class RootKind {
    proper,   // Newton converged: a transversal (or at least isolated) root, exact to ~1e-17
    singular, // Newton failed but the ray passes within rounding of the surface
              // (a collapsed edge such as the teapot's lid apex): a real hit
    tangent   // the ray passes within `distance` of the surface without a root found: a near
              // miss, or a touch the caller may accept if `distance` is within its tolerance
};

struct Root {
    int patch = -1;
    real u = 0, v = 0, t = 0;
    real distance = 0;  // distance of S(u, v) from the ray (rounding level for proper roots)
    real sin_angle = 0; // sine of the angle between the ray and the tangent plane (0 if undefined)
    // How robust the root is: the largest depth by which the ray dips through the surface
    // before the surface's curvature brings it back (tan^2(angle) / (2 normal curvature);
    // infinite for a flat direction or an undefined normal). A ray exactly tangent in real
    // arithmetic, rounded to double, crosses or misses the surface by ~1e-17: its roots have
    // a dip far below the rounding of any double-precision computation.
    real dip = 0;
    bool degenerate_normal = false; // dS/du x dS/dv vanishes (collapsed edge)
    RootKind kind = RootKind::proper;
};

struct Options {
    real leaf_size = 0;         // box extent that ends subdivision; 0: 1e-6 * model diagonal
    real near_distance = 0;     // hulls are padded by this, and near misses within it are
                                // reported as tangent roots; 0: 2e-9 * model diagonal
    size_t max_nodes = 4000000; // work bound per ray: above it the ray is undecided
};

struct Result {
    bool decided = true;     // false: the work bound was hit, `roots` is incomplete
    std::vector<Root> roots; // all roots with t in [tnear, tfar], sorted by t (then patch);
                             // roots of different patches at one point (seams) are all kept
    size_t nodes = 0;        // sub-patches visited
    size_t leaves = 0;
};

class Intersector {
public:
    explicit Intersector(std::vector<Patch> patches, Options options = {});

    const std::vector<Patch> &patches() const { return patches_; }
    real diagonal() const { return diagonal_; }
    void bounds(real lower[3], real upper[3]) const;

    // All roots of o + t d (t in [tnear, tfar]) with every patch.
    Result intersect(const real o[3], const real d[3], real tnear, real tfar) const;

private:
    void intersect_patch(int index, const real o[3], const real d[3], real tnear, real tfar, Result &result) const;

    std::vector<Patch> patches_;
    Options options_;
    real lower_[3], upper_[3];
    real diagonal_ = 0;
};

// Small long-double vector helpers for building rays through reference surface points.
inline void normalize(real v[3]) {
    const real l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; ++c) v[c] /= l;
}
inline void cross(const real a[3], const real b[3], real c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

} // namespace ref
