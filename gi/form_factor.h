#pragma once
/// Form factors between diffuse surfaces (Cohen & Wallace 1993, ch. 4), the coupling
/// coefficients of radiosity: F_ij is the fraction of the power leaving patch i (uniformly,
/// Lambertian) that arrives at patch j,
///   F_ij = 1/A_i ∫_{A_i} ∫_{A_j} V(x, y) cos θ_x cos θ_y / (π r²) dA_y dA_x,
/// reciprocal: A_i F_ij = A_j F_ji.
///
/// Method used here: point-to-polygon. At each of N stratified points x_k on patch i, the
/// unoccluded differential form factor to polygon j is Lambert's closed form (below); it is
/// multiplied by the visibility of one ray from x_k to a stratified point y_k on j, and the
/// products are averaged. Without occluders this is the midpoint rule on an exact integrand:
/// error O(h²) in the sample spacing h, no noise; occlusion adds the noise of the visible
/// fraction.
#include "core/math.h"

#include <functional>

namespace kasumi {

/// Unoccluded form factor (dimensionless, in [0, 1]) from a differential area at x with unit
/// normal n to the convex planar polygon `vertices` (count >= 3), whose front side is the one it
/// winds counter-clockwise toward (polygon_normal): zero if x lies behind the polygon. The part
/// of the polygon below x's tangent plane is clipped away first. Lambert's formula (Lambert 1760;
/// Baum, Rushmeier & Winget 1989, eq. 3; Cohen & Wallace 1993, eq. 4.19):
///   F = 1/(2π) Σ_i Θ_i n · (r_i × r_{i+1}) / |r_i × r_{i+1}|,  r_i = v_i − x, Θ_i = angle(r_i,
///   r_{i+1}),
/// with the vertices ordered clockwise as seen from x (the front side faces x).
/// `count` is at most kMaxFormFactorVertices.
double point_to_polygon_form_factor(const DVec3& x, const DVec3& n, const DVec3* vertices,
                                    int count);

/// The most vertices point_to_polygon_form_factor takes.
inline constexpr int kMaxFormFactorVertices = 64;

/// A planar convex patch (triangle or parallelogram-like quad) with its front normal and area;
/// points on it are drawn by `point(u, v)` for (u, v) in [0, 1]² (area-uniform for
/// parallelograms and, through the fold, for triangles).
struct FormFactorPatch {
    DVec3 vertices[4];
    int count = 4;  ///< 3 or 4
    DVec3 normal{0.0, 0.0, 1.0};
    double area = 0.0;
};

/// Builds a FormFactorPatch (normal by Newell's method, area) from 3 or 4 vertices.
FormFactorPatch make_form_factor_patch(const Vec3* vertices, int count);

/// A point of the patch for (u, v) in [0, 1]²: bilinear on quads, folded barycentric on
/// triangles; uniform in area for parallelograms and triangles.
DVec3 patch_point(const FormFactorPatch& p, double u, double v);

/// F_ij from patch i to patch j by the point-to-polygon method with n × n stratified points on
/// i (their centres when jitter is empty) and, when `visible` is given, one visibility test per
/// point toward a stratified point of j (visible(x, y) true when the segment is clear).
/// `jitter` (may be empty) returns uniform numbers in [0, 1) for jittered sampling.
double form_factor(const FormFactorPatch& i, const FormFactorPatch& j, int n,
                   const std::function<bool(const DVec3&, const DVec3&)>& visible = {},
                   const std::function<double()>& jitter = {});

}  // namespace kasumi
