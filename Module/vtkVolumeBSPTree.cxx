// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkVolumeBSPTree.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace
{
using glm::dvec3;
using glm::dvec4;
using Node = vtkVolumeBSPTree::Node;
using Fragment = vtkVolumeBSPTree::Fragment;

constexpr double Inf = std::numeric_limits<double>::infinity();

struct Face
{
  dvec4 Plane;                 // unit outward normal and offset
  std::vector<dvec3> Vertices; // counter-clockwise seen from outside
};
using Polyhedron = std::vector<Face>;

enum class Side
{
  Inside,
  Outside,
  Cut
};

double Distance(const dvec4& plane, const dvec3& x)
{
  return plane.x * x.x + plane.y * x.y + plane.z * x.z + plane.w;
}

vtkVolumeBSPTree::Plane ToPlane(const dvec4& p)
{
  return { { p.x, p.y, p.z, p.w } };
}

dvec4 FromPlane(const vtkVolumeBSPTree::Plane& p)
{
  return dvec4(p[0], p[1], p[2], p[3]);
}

// Within tol of the plane counts as on it, so a polyhedron is cut only when it reaches more than
// tol beyond the plane on both sides; a flat one counts as outside (it holds no volume).
Side Classify(const Polyhedron& poly, const dvec4& plane, double tol)
{
  double lo = Inf;
  double hi = -Inf;
  for (const Face& f : poly)
  {
    for (const dvec3& v : f.Vertices)
    {
      const double d = Distance(plane, v);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  if (lo >= -tol)
  {
    return Side::Outside;
  }
  return hi <= tol ? Side::Inside : Side::Cut;
}

bool Less(const dvec3& a, const dvec3& b)
{
  return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}

// Keeps the part with n.x + d <= 0 and closes it with a cap on the plane. Vertices within tol of
// the plane stay where they are and join the cap. An edge is cut from its end points taken in a
// fixed order, so its two faces get the bit-identical point and the pieces stay watertight.
void Clip(const Polyhedron& in, const dvec4& plane, double tol, Polyhedron& out)
{
  out.clear();
  std::vector<dvec3> cap;
  std::vector<double> dist;
  std::vector<int> side;
  for (const Face& f : in)
  {
    const size_t n = f.Vertices.size();
    dist.resize(n);
    side.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
      dist[i] = Distance(plane, f.Vertices[i]);
      side[i] = dist[i] < -tol ? -1 : (dist[i] > tol ? 1 : 0);
    }
    Face g;
    g.Plane = f.Plane;
    bool inside = false;
    for (size_t i = 0; i < n; ++i)
    {
      const size_t j = (i + 1) % n;
      const dvec3& a = f.Vertices[i];
      const dvec3& b = f.Vertices[j];
      if (side[i] <= 0)
      {
        g.Vertices.push_back(a);
        inside = inside || side[i] < 0;
        if (side[i] == 0)
        {
          cap.push_back(a);
        }
      }
      if (side[i] * side[j] < 0)
      {
        const dvec3 p = Less(a, b) ? a + (b - a) * (dist[i] / (dist[i] - dist[j]))
                                   : b + (a - b) * (dist[j] / (dist[j] - dist[i]));
        g.Vertices.push_back(p);
        cap.push_back(p);
      }
    }
    // A face only touching the plane from outside, or lying in it, is replaced by the cap.
    if (inside && g.Vertices.size() >= 3)
    {
      out.push_back(std::move(g));
    }
  }

  // Points on the plane are shared by two or more faces: merge them, then order them
  // counter-clockwise around their centroid as seen from outside (along +n).
  std::vector<dvec3> unique;
  for (const dvec3& p : cap)
  {
    bool found = false;
    for (const dvec3& q : unique)
    {
      const dvec3 e = p - q;
      if (glm::dot(e, e) <= tol * tol)
      {
        found = true;
        break;
      }
    }
    if (!found)
    {
      unique.push_back(p);
    }
  }
  if (unique.size() < 3)
  {
    return;
  }
  const dvec3 n(plane);
  dvec3 c(0.0);
  for (const dvec3& p : unique)
  {
    c += p;
  }
  c /= static_cast<double>(unique.size());
  const dvec3 an = glm::abs(n);
  const dvec3 axis = an.x <= an.y && an.x <= an.z ? dvec3(1, 0, 0)
                                                  : (an.y <= an.z ? dvec3(0, 1, 0) : dvec3(0, 0, 1));
  const dvec3 u = glm::normalize(glm::cross(n, axis));
  const dvec3 v = glm::cross(n, u); // u x v = n
  std::vector<std::pair<double, dvec3>> ring;
  ring.reserve(unique.size());
  for (const dvec3& p : unique)
  {
    ring.emplace_back(std::atan2(glm::dot(p - c, v), glm::dot(p - c, u)), p);
  }
  std::sort(ring.begin(), ring.end(),
    [](const std::pair<double, dvec3>& a, const std::pair<double, dvec3>& b)
    { return a.first < b.first; });
  Face capFace;
  capFace.Plane = plane;
  for (const auto& r : ring)
  {
    capFace.Vertices.push_back(r.second);
  }
  out.push_back(std::move(capFace));
}

Polyhedron MakeAxisBox(const dvec3& lo, const dvec3& hi)
{
  const dvec3 p[8] = { { lo.x, lo.y, lo.z }, { hi.x, lo.y, lo.z }, { hi.x, hi.y, lo.z },
    { lo.x, hi.y, lo.z }, { lo.x, lo.y, hi.z }, { hi.x, lo.y, hi.z }, { hi.x, hi.y, hi.z },
    { lo.x, hi.y, hi.z } };
  return {
    { dvec4(-1, 0, 0, lo.x), { p[0], p[4], p[7], p[3] } },
    { dvec4(1, 0, 0, -hi.x), { p[1], p[2], p[6], p[5] } },
    { dvec4(0, -1, 0, lo.y), { p[0], p[1], p[5], p[4] } },
    { dvec4(0, 1, 0, -hi.y), { p[3], p[7], p[6], p[2] } },
    { dvec4(0, 0, -1, lo.z), { p[0], p[3], p[2], p[1] } },
    { dvec4(0, 0, 1, -hi.z), { p[4], p[5], p[6], p[7] } },
  };
}

struct BoxGeometry
{
  int Index; // into the input boxes
  int VolumeId;
  dvec4 Planes[6]; // -u0, +u0, -u1, +u1, -u2, +u2
};

struct Partial
{
  int Box;         // into the geometry list
  Polyhedron Part; // the box clipped to the cell
};

class Builder
{
public:
  Builder(const std::vector<BoxGeometry>& geometry, double tol, std::vector<Node>& nodes,
    std::vector<Fragment>& fragments)
    : Geometry(geometry)
    , Tol(tol)
    , Nodes(nodes)
    , Fragments(fragments)
  {
  }

  int Split(const Polyhedron& cell, std::vector<int> covering, const std::vector<int>& candidates,
    int depth);

  int Depth = 0;

private:
  int MakeLeaf(const Polyhedron& cell, const std::vector<int>& covering);

  const std::vector<BoxGeometry>& Geometry;
  double Tol;
  std::vector<Node>& Nodes;
  std::vector<Fragment>& Fragments;
};

int Builder::Split(
  const Polyhedron& cell, std::vector<int> covering, const std::vector<int>& candidates, int depth)
{
  this->Depth = std::max(this->Depth, depth);

  // Each candidate box contains the cell, misses it, or covers part of it. Clipping plane by
  // plane is exact where a corner test is not (a box can miss a cell that is inside none of its
  // planes' outsides), and the part is what the split cost below is measured on.
  std::vector<Partial> partial;
  Polyhedron scratch;
  for (int b : candidates)
  {
    const BoxGeometry& g = this->Geometry[b];
    Polyhedron part;
    bool clipped = false;
    bool missed = false;
    for (const dvec4& plane : g.Planes)
    {
      const Side s = Classify(clipped ? part : cell, plane, this->Tol);
      if (s == Side::Outside)
      {
        missed = true;
        break;
      }
      if (s == Side::Cut)
      {
        Clip(clipped ? part : cell, plane, this->Tol, scratch);
        part.swap(scratch);
        clipped = true;
        if (part.size() < 4)
        {
          missed = true;
          break;
        }
      }
    }
    if (missed)
    {
      continue;
    }
    if (clipped)
    {
      partial.push_back({ b, std::move(part) });
    }
    else
    {
      covering.push_back(b);
    }
  }
  if (partial.empty())
  {
    return this->MakeLeaf(cell, covering);
  }

  // The first plane that clipped a partial box cut the cell itself, so a candidate exists. Cost:
  // partial boxes the plane cuts inside the cell (each may add a fragment); covering boxes are
  // cut by every candidate alike and do not count.
  int bestStraddles = std::numeric_limits<int>::max();
  bool bestTrims = false;
  dvec4 best(0.0);
  for (const Partial& p : partial)
  {
    for (const dvec4& plane : this->Geometry[p.Box].Planes)
    {
      if (Classify(cell, plane, this->Tol) != Side::Cut)
      {
        continue;
      }
      int straddles = 0;
      bool trims = covering.empty(); // nothing outside the plane: a free cut
      for (const Partial& q : partial)
      {
        if (&q == &p)
        {
          continue;
        }
        const Side s = Classify(q.Part, plane, this->Tol);
        if (s == Side::Cut)
        {
          ++straddles;
        }
        if (s != Side::Inside)
        {
          trims = false;
        }
        if (straddles > bestStraddles)
        {
          break;
        }
      }
      if (straddles < bestStraddles || (straddles == bestStraddles && trims && !bestTrims))
      {
        bestStraddles = straddles;
        bestTrims = trims;
        best = plane;
      }
    }
  }
  // Each split removes a plane from the set cutting the cell, so depth is bounded by the plane
  // count; this guard only catches rounding gone wrong and keeps the union covered.
  if (bestStraddles == std::numeric_limits<int>::max() ||
    depth > 6 * static_cast<int>(this->Geometry.size()) + 8)
  {
    for (const Partial& p : partial)
    {
      covering.push_back(p.Box);
    }
    return this->MakeLeaf(cell, covering);
  }

  std::vector<int> inside;
  std::vector<int> outside;
  for (const Partial& q : partial)
  {
    const Side s = Classify(q.Part, best, this->Tol);
    if (s != Side::Outside)
    {
      inside.push_back(q.Box);
    }
    if (s != Side::Inside)
    {
      outside.push_back(q.Box);
    }
  }
  partial.clear();
  Polyhedron in;
  Polyhedron out;
  Clip(cell, best, this->Tol, in);
  Clip(cell, -best, this->Tol, out);

  const int node = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes[node].Split = ToPlane(best);
  const int inChild = this->Split(in, covering, inside, depth + 1);
  const int outChild = this->Split(out, std::move(covering), outside, depth + 1);
  this->Nodes[node].Inside = inChild;
  this->Nodes[node].Outside = outChild;
  return node;
}

int Builder::MakeLeaf(const Polyhedron& cell, const std::vector<int>& covering)
{
  if (covering.empty())
  {
    return -1; // empty space: the solid-leaf tree drops it
  }
  Fragment f;
  std::vector<std::pair<int, int>> ids; // (volume id, box index)
  for (int b : covering)
  {
    ids.emplace_back(this->Geometry[b].VolumeId, this->Geometry[b].Index);
  }
  std::sort(ids.begin(), ids.end());
  for (const auto& id : ids)
  {
    f.VolumeIds.push_back(id.first);
    f.BoxIndices.push_back(id.second);
  }

  // Share vertices between faces (the clipper keeps them within tol of each other).
  std::vector<dvec3> vertices;
  for (const Face& face : cell)
  {
    std::vector<int> loop;
    for (const dvec3& p : face.Vertices)
    {
      int index = -1;
      for (size_t k = 0; k < vertices.size(); ++k)
      {
        const dvec3 e = p - vertices[k];
        if (glm::dot(e, e) <= this->Tol * this->Tol)
        {
          index = static_cast<int>(k);
          break;
        }
      }
      if (index < 0)
      {
        index = static_cast<int>(vertices.size());
        vertices.push_back(p);
      }
      if (loop.empty() || loop.back() != index)
      {
        loop.push_back(index);
      }
    }
    while (loop.size() > 1 && loop.front() == loop.back())
    {
      loop.pop_back();
    }
    if (loop.size() < 3)
    {
      continue;
    }
    f.Planes.push_back(ToPlane(face.Plane));
    for (size_t k = 1; k + 1 < loop.size(); ++k)
    {
      f.Triangles.insert(f.Triangles.end(), { loop[0], loop[k], loop[k + 1] });
    }
    f.Faces.push_back(std::move(loop));
  }
  dvec3 c(0.0);
  for (const dvec3& v : vertices)
  {
    c += v;
    f.Vertices.push_back({ { v.x, v.y, v.z } });
  }
  c /= static_cast<double>(std::max<size_t>(1, vertices.size()));
  // Divergence theorem over the outward triangles, relative to an interior point.
  double volume = 0.0;
  for (size_t t = 0; t + 2 < f.Triangles.size(); t += 3)
  {
    const dvec3 a = vertices[f.Triangles[t]] - c;
    const dvec3 b = vertices[f.Triangles[t + 1]] - c;
    const dvec3 d = vertices[f.Triangles[t + 2]] - c;
    volume += glm::dot(a, glm::cross(b, d));
  }
  f.Volume = volume / 6.0;

  const int node = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes[node].Split = { { 0.0, 0.0, 0.0, 0.0 } };
  this->Nodes[node].Fragment = static_cast<int>(this->Fragments.size());
  this->Fragments.push_back(std::move(f));
  return node;
}
}

bool vtkVolumeBSPTree::SetBoxes(const std::vector<Box>& boxes)
{
  if (boxes == this->Boxes)
  {
    return false;
  }
  this->Boxes = boxes;
  this->NeedsBuild = true;
  return true;
}

void vtkVolumeBSPTree::SetRelativeTolerance(double tolerance)
{
  if (tolerance != this->RelativeTolerance)
  {
    this->RelativeTolerance = tolerance;
    this->NeedsBuild = true;
  }
}

bool vtkVolumeBSPTree::Update()
{
  if (!this->NeedsBuild)
  {
    return false;
  }
  this->Build();
  return true;
}

void vtkVolumeBSPTree::Build()
{
  this->NeedsBuild = false;
  this->Nodes.clear();
  this->Fragments.clear();
  this->Root = -1;
  this->Depth = 0;
  this->Tolerance = 0.0;
  this->Origin = { { 0.0, 0.0, 0.0 } };
  if (this->Boxes.empty())
  {
    return;
  }

  // Columns of the affine part and the translation, relative to the centre of the first box:
  // differences of UTM-sized numbers are exact enough, products of them would not be.
  auto columns = [](const Box& box, dvec3 a[3], dvec3& t)
  {
    const auto& m = box.Matrix;
    for (int j = 0; j < 3; ++j)
    {
      a[j] = dvec3(m[j], m[4 + j], m[8 + j]);
    }
    t = dvec3(m[3], m[7], m[11]);
  };
  dvec3 a[3];
  dvec3 t;
  columns(this->Boxes[0], a, t);
  const dvec3 origin = t + 0.5 * (a[0] + a[1] + a[2]);
  this->Origin = { { origin.x, origin.y, origin.z } };

  dvec3 lo(Inf);
  dvec3 hi(-Inf);
  for (const Box& box : this->Boxes)
  {
    columns(box, a, t);
    t -= origin;
    for (int k = 0; k < 8; ++k)
    {
      const dvec3 p =
        t + double(k & 1) * a[0] + double((k >> 1) & 1) * a[1] + double((k >> 2) & 1) * a[2];
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const double diagonal = glm::length(hi - lo);
  const double tol = this->RelativeTolerance * (diagonal > 0.0 ? diagonal : 1.0);
  this->Tolerance = tol;

  std::vector<BoxGeometry> geometry;
  for (size_t i = 0; i < this->Boxes.size(); ++i)
  {
    columns(this->Boxes[i], a, t);
    t -= origin;
    BoxGeometry g;
    g.Index = static_cast<int>(i);
    g.VolumeId = this->Boxes[i].VolumeId;
    bool thin = false;
    for (int k = 0; k < 3; ++k)
    {
      // Cross products of the other two edges: correct for shear and mirroring too.
      dvec3 n = glm::cross(a[(k + 1) % 3], a[(k + 2) % 3]);
      const double len = glm::length(n);
      const double h = len > 0.0 ? std::abs(glm::dot(n, a[k])) / len : 0.0;
      if (!(h > tol))
      {
        thin = true;
        break;
      }
      n /= len;
      if (glm::dot(n, a[k]) < 0.0)
      {
        n = -n;
      }
      g.Planes[2 * k] = dvec4(-n, glm::dot(n, t));
      g.Planes[2 * k + 1] = dvec4(n, -glm::dot(n, t + a[k]));
    }
    if (!thin)
    {
      geometry.push_back(g);
    }
  }
  if (geometry.empty())
  {
    return;
  }

  // Padding keeps the root's own planes off every box, so no fragment has a face on them.
  const dvec3 pad(0.01 * diagonal + tol);
  const Polyhedron root = MakeAxisBox(lo - pad, hi + pad);
  std::vector<int> candidates(geometry.size());
  for (size_t i = 0; i < geometry.size(); ++i)
  {
    candidates[i] = static_cast<int>(i);
  }
  Builder builder(geometry, tol, this->Nodes, this->Fragments);
  this->Root = builder.Split(root, {}, candidates, 0);
  this->Depth = builder.Depth;
}

int vtkVolumeBSPTree::GetMaximumOverlap() const
{
  size_t m = 0;
  for (const Fragment& f : this->Fragments)
  {
    m = std::max(m, f.VolumeIds.size());
  }
  return static_cast<int>(m);
}

int vtkVolumeBSPTree::FindFragment(const Vector3& worldPoint) const
{
  const dvec3 p(worldPoint[0] - this->Origin[0], worldPoint[1] - this->Origin[1],
    worldPoint[2] - this->Origin[2]);
  int node = this->Root;
  while (node >= 0)
  {
    const Node& n = this->Nodes[node];
    if (n.Fragment >= 0)
    {
      return n.Fragment;
    }
    node = Distance(FromPlane(n.Split), p) <= 0.0 ? n.Inside : n.Outside;
  }
  return -1;
}

bool vtkVolumeBSPTree::FragmentContainsPoint(int i, const Vector3& worldPoint) const
{
  const dvec3 p(worldPoint[0] - this->Origin[0], worldPoint[1] - this->Origin[1],
    worldPoint[2] - this->Origin[2]);
  for (const Plane& plane : this->Fragments[i].Planes)
  {
    if (Distance(FromPlane(plane), p) > 0.0)
    {
      return false;
    }
  }
  return true;
}

void vtkVolumeBSPTree::Collect(int node, const Vector3& localEye, bool parallel,
  const Vector3& direction, std::vector<int>& order) const
{
  if (node < 0)
  {
    return;
  }
  const Node& n = this->Nodes[node];
  if (n.Fragment >= 0)
  {
    order.push_back(n.Fragment);
    return;
  }
  const Plane& s = n.Split;
  // The side rays start on comes first. An eye on the plane sees either side only through
  // itself, and rays parallel to the plane never cross it: then either order is right.
  const bool insideFirst = parallel
    ? s[0] * direction[0] + s[1] * direction[1] + s[2] * direction[2] >= 0.0
    : s[0] * localEye[0] + s[1] * localEye[1] + s[2] * localEye[2] + s[3] <= 0.0;
  this->Collect(insideFirst ? n.Inside : n.Outside, localEye, parallel, direction, order);
  this->Collect(insideFirst ? n.Outside : n.Inside, localEye, parallel, direction, order);
}

void vtkVolumeBSPTree::SortFrontToBack(
  const Vector3& eye, bool parallel, const Vector3& direction, std::vector<int>& order) const
{
  order.clear();
  order.reserve(this->Fragments.size());
  const Vector3 local = { { eye[0] - this->Origin[0], eye[1] - this->Origin[1],
    eye[2] - this->Origin[2] } };
  this->Collect(this->Root, local, parallel, direction, order);
}

void vtkVolumeBSPTree::SortBackToFront(
  const Vector3& eye, bool parallel, const Vector3& direction, std::vector<int>& order) const
{
  this->SortFrontToBack(eye, parallel, direction, order);
  std::reverse(order.begin(), order.end());
}
