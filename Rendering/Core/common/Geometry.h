// Geometry: pure functions building slice proxy geometry for the AccelVolume mappers.
#ifndef accelvolume_Geometry_h
#define accelvolume_Geometry_h

#include <cmath>
#include <vector>

namespace accelvolume
{

struct Vec3
{
  double x = 0, y = 0, z = 0;
};

// Inline: these sit in the inner loops of the reference renderer.
inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}

inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}

inline Vec3 operator-(const Vec3& a)
{
  return { -a.x, -a.y, -a.z };
}

inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a.x, s * a.y, s * a.z };
}

inline Vec3 operator*(const Vec3& a, double s)
{
  return s * a;
}

inline double Dot(const Vec3& a, const Vec3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}

inline double Length(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}

// Returns the zero vector for a zero input rather than NaNs.
inline Vec3 Normalize(const Vec3& a)
{
  const double length = Length(a);
  return length > 0 ? a * (1.0 / length) : Vec3{};
}

// Keeps the points p with Dot(normal, p) + offset >= 0.
struct HalfSpace
{
  Vec3 normal;
  double offset = 0;
};

// Axis-aligned and inclusive: a box with lower == upper on some axis is flat but not empty.
struct Box
{
  Vec3 lower, upper;
  bool IsEmpty() const; // true when lower > upper on any axis
};

// Convex, vertices in order with consistent winding.
using Polygon = std::vector<Vec3>;

// The six half-spaces whose intersection is the box.
std::vector<HalfSpace> BoxHalfSpaces(const Box& box);

// Sutherland-Hodgman clip of a convex polygon. Duplicate consecutive vertices are removed and
// degenerate results (fewer than 3 vertices, or zero area relative to the polygon size) come back
// empty, so callers never see slivers from flat regions.
Polygon ClipPolygon(const Polygon& polygon, const HalfSpace& halfSpace);

// Area of a planar polygon (0 for fewer than 3 vertices).
double PolygonArea(const Polygon& polygon);

// Polygon of the plane Dot(normal, p) == value inside box and all half-spaces, wound
// counterclockwise seen from the side normal points to (its right-hand normal is +normal).
// Empty when the plane misses the region, the normal is zero, or the section has no area.
Polygon PlaneRegionPolygon(
  const Vec3& normal, double value, const Box& box, const std::vector<HalfSpace>& clip);

struct SliceStack
{
  std::vector<Polygon> polygons;
  std::vector<double> depths; // depths[n] is the depth of polygons[n]
};

enum class SliceOrder
{
  FrontToBack,
  BackToFront
};

// View-aligned proxy slices through the convex region box ∩ clip.
// depth(p) = Dot(depthGradient, p) + depthOffset grows away from the viewer. Slices lie at depths
// phase + k * spacing (all integers k) strictly inside the depth range of the region; polygons
// without area are dropped. Each polygon faces the viewer (counterclockwise seen from the side
// where depth decreases). A region without volume (a flat box, or clip planes leaving only a
// plane) gives no slices: callers wanting such data drawn should pad the box, e.g. by half a voxel
// to the texture extent. Spacing <= 0 or a zero gradient gives no slices.
// Integer range [first, last] of the sample depths phase + k * spacing lying strictly inside
// (minimumDepth, maximumDepth), robust to rounding; first > last when there is none.
void SampleIndexRange(double minimumDepth, double maximumDepth, double phase, double spacing,
  long long& first, long long& last);

// Depth range (depth(p) = Dot(depthGradient, p) + depthOffset) of the region box ∩ clip; false
// when the region has no depth extent (empty, or flat across the view direction).
bool RegionDepthRange(const Box& region, const std::vector<HalfSpace>& clip,
  const Vec3& depthGradient, double depthOffset, double& minimumDepth, double& maximumDepth);

SliceStack ComputeViewAlignedSlices(const Box& region, const std::vector<HalfSpace>& clip,
  const Vec3& depthGradient, double depthOffset, double spacing, double phase, SliceOrder order);

// Boundary faces of the convex region box ∩ clip, each wound counterclockwise seen from outside
// (right-hand normal points outward): the 6 box faces clipped by the half-spaces, then each
// half-space's plane polygon clipped by the box and the other half-spaces. Faces without area are
// dropped; a half-space plane coinciding with a box face of the same orientation, or with an
// earlier half-space, adds no second copy. A box flat along one axis gives its rectangle twice
// (front and back windings); flatter boxes give nothing.
std::vector<Polygon> ComputeRegionBoundaryFaces(
  const Box& region, const std::vector<HalfSpace>& clip);

// VTK cropping. planes = {x0, x1, y0, y1, z0, z1} in the same coordinates as volume; flags is VTK's
// 27-bit region mask: region index i + 3 * j + 9 * k with i, j, k in {0, 1, 2} along x, y, z
// (0 = below the low plane, 1 = between the planes, 2 = above the high plane); a set bit makes the
// region visible. Planes are clamped into the volume and each pair sorted. As in VTK, points on a
// plane belong to the middle region, so an outer region of zero thickness does not exist and is
// dropped while the middle one always exists (possibly flat). Visible regions are merged greedily
// into larger boxes where their union is a box (all 27 visible gives the volume itself); the boxes
// returned only share boundaries.
std::vector<Box> CroppingRegionBoxes(const Box& volume, const double planes[6], int flags);

// Fan triangulation of a convex polygon appended to xyz (9 floats per triangle).
void AppendTriangleFan(const Polygon& polygon, std::vector<float>& xyz);

// Parametric interval [t0, t1] of the whole line origin + t * direction inside box ∩ clip (t is
// not restricted to t >= 0; callers clamp). Returns false when empty. A zero direction gives
// (-inf, +inf) when the origin is inside. A single touching point gives t0 == t1 and true.
bool IntersectRayRegion(const Vec3& origin, const Vec3& direction, const Box& box,
  const std::vector<HalfSpace>& clip, double& t0, double& t1);

} // namespace accelvolume

#endif
