// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeBSPTree.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace strata
{

namespace
{
using glm::dvec3;
using glm::dvec4;
using Node = VolumeBSPTree::Node;
using Fragment = VolumeBSPTree::Fragment;

constexpr double Inf = std::numeric_limits<double>::infinity();

// Convex polyhedron with shared points: a cut edge yields one point for both its faces, so the
// pieces stay watertight without merging by distance.
struct Polyhedron
{
  std::vector<dvec3> Points;
  std::vector<dvec4> Planes;        // one per face: unit outward normal and offset
  std::vector<int> Offsets = { 0 }; // face f is Loops[Offsets[f], Offsets[f + 1])
  std::vector<int> Loops;           // point indices, counter-clockwise seen from outside

  void Clear()
  {
    this->Points.clear();
    this->Planes.clear();
    this->Offsets.assign(1, 0);
    this->Loops.clear();
  }
  void AddFace(const dvec4& plane)
  {
    this->Planes.push_back(plane);
    this->Offsets.push_back(static_cast<int>(this->Loops.size()));
  }
};

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

VolumeBSPTree::Plane ToPlane(const dvec4& p)
{
  return { { p.x, p.y, p.z, p.w } };
}

dvec4 FromPlane(const VolumeBSPTree::Plane& p)
{
  return dvec4(p[0], p[1], p[2], p[3]);
}

// Within tol of the plane counts as on it, so a polyhedron is cut only when it reaches more than
// tol beyond the plane on both sides; a flat one counts as outside (it holds no volume).
Side Classify(const Polyhedron& poly, const dvec4& plane, double tol)
{
  double lo = Inf;
  double hi = -Inf;
  for (const dvec3& v : poly.Points)
  {
    const double d = Distance(plane, v);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  if (lo >= -tol)
  {
    return Side::Outside;
  }
  return hi <= tol ? Side::Inside : Side::Cut;
}

struct ClipScratch
{
  std::vector<double> Distances;
  std::vector<int> Sides;
  std::vector<int> Remap;
  std::vector<int> Cap;
  std::vector<std::array<int, 3>> Edges; // (lower point, higher point, new point)
  std::vector<std::pair<double, int>> Ring;
};

// Keeps the part with n.x + d <= 0 and closes it with a cap on the plane. Points within tol of
// the plane stay where they are and join the cap, so nearly coplanar planes add no slivers.
void Clip(const Polyhedron& in, const dvec4& plane, double tol, Polyhedron& out, ClipScratch& s)
{
  out.Clear();
  const size_t nv = in.Points.size();
  s.Distances.resize(nv);
  s.Sides.resize(nv);
  s.Remap.resize(nv);
  s.Cap.clear();
  s.Edges.clear();
  for (size_t v = 0; v < nv; ++v)
  {
    const double d = Distance(plane, in.Points[v]);
    s.Distances[v] = d;
    s.Sides[v] = d < -tol ? -1 : (d > tol ? 1 : 0);
    s.Remap[v] = -1;
    if (s.Sides[v] <= 0)
    {
      s.Remap[v] = static_cast<int>(out.Points.size());
      out.Points.push_back(in.Points[v]);
      if (s.Sides[v] == 0)
      {
        s.Cap.push_back(s.Remap[v]);
      }
    }
  }
  auto edgePoint = [&](int a, int b)
  {
    const int lo = std::min(a, b);
    const int hi = std::max(a, b);
    for (const auto& e : s.Edges)
    {
      if (e[0] == lo && e[1] == hi)
      {
        return e[2];
      }
    }
    const int index = static_cast<int>(out.Points.size());
    const double t = s.Distances[lo] / (s.Distances[lo] - s.Distances[hi]);
    out.Points.push_back(in.Points[lo] + (in.Points[hi] - in.Points[lo]) * t);
    s.Cap.push_back(index);
    s.Edges.push_back({ { lo, hi, index } });
    return index;
  };
  for (size_t f = 0; f < in.Planes.size(); ++f)
  {
    const int begin = in.Offsets[f];
    const int n = in.Offsets[f + 1] - begin;
    const size_t start = out.Loops.size();
    bool inside = false;
    for (int i = 0; i < n; ++i)
    {
      const int a = in.Loops[begin + i];
      const int b = in.Loops[begin + (i + 1) % n];
      if (s.Sides[a] <= 0)
      {
        out.Loops.push_back(s.Remap[a]);
        inside = inside || s.Sides[a] < 0;
      }
      if (s.Sides[a] * s.Sides[b] < 0)
      {
        out.Loops.push_back(edgePoint(a, b));
      }
    }
    // A face only touching the plane from outside, or lying in it, is replaced by the cap.
    if (inside && out.Loops.size() - start >= 3)
    {
      out.AddFace(in.Planes[f]);
    }
    else
    {
      out.Loops.resize(start);
    }
  }
  if (s.Cap.size() < 3)
  {
    out.Clear(); // only when the plane does not really cut: the caller checks first
    return;
  }

  // The cap is convex: order its points counter-clockwise around their centroid seen along +n.
  const dvec3 n(plane);
  dvec3 c(0.0);
  for (int i : s.Cap)
  {
    c += out.Points[i];
  }
  c /= static_cast<double>(s.Cap.size());
  const dvec3 an = glm::abs(n);
  const dvec3 axis = an.x <= an.y && an.x <= an.z
                       ? dvec3(1, 0, 0)
                       : (an.y <= an.z ? dvec3(0, 1, 0) : dvec3(0, 0, 1));
  const dvec3 u = glm::normalize(glm::cross(n, axis));
  const dvec3 v = glm::cross(n, u); // u x v = n
  s.Ring.clear();
  for (int i : s.Cap)
  {
    const dvec3 e = out.Points[i] - c;
    s.Ring.emplace_back(std::atan2(glm::dot(e, v), glm::dot(e, u)), i);
  }
  std::sort(s.Ring.begin(), s.Ring.end());
  for (const auto& r : s.Ring)
  {
    out.Loops.push_back(r.second);
  }
  out.AddFace(plane);
}

void MakeAxisBox(const dvec3& lo, const dvec3& hi, Polyhedron& box)
{
  box.Clear();
  for (int k = 0; k < 8; ++k)
  {
    box.Points.emplace_back(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
  }
  const int loops[6][4] = {
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 }
  };
  const dvec4 planes[6] = { dvec4(-1, 0, 0, lo.x),
    dvec4(1, 0, 0, -hi.x),
    dvec4(0, -1, 0, lo.y),
    dvec4(0, 1, 0, -hi.y),
    dvec4(0, 0, -1, lo.z),
    dvec4(0, 0, 1, -hi.z) };
  for (int f = 0; f < 6; ++f)
  {
    box.Loops.insert(box.Loops.end(), loops[f], loops[f] + 4);
    box.AddFace(planes[f]);
  }
}

struct BoxGeometry
{
  int Index; // into the input boxes
  int VolumeId;
  dvec4 Planes[6]; // -u0, +u0, -u1, +u1, -u2, +u2
};

// A box that covers part of a cell, with that part: the split cost is measured on it.
struct Partial
{
  int Box; // into the geometry list
  Polyhedron Part;
  int Cuts = 0; // bit f: plane f of the box cuts the cell
};

class Builder
{
public:
  Builder(const std::vector<BoxGeometry>& geometry,
    double tol,
    std::vector<Node>& nodes,
    std::vector<Fragment>& fragments)
    : Geometry(geometry)
    , Tol(tol)
    , Nodes(nodes)
    , Fragments(fragments)
  {
  }

  int Build(const dvec3& lo, const dvec3& hi);

  int Depth = 0;

private:
  int Split(Polyhedron cell, std::vector<int> covering, std::vector<Partial> partial, int depth);
  int MakeLeaf(const Polyhedron& cell, const std::vector<int>& covering);

  // Polyhedra are recycled: a build makes thousands and their vectors keep their capacity.
  Polyhedron Acquire()
  {
    if (this->Pool.empty())
    {
      return Polyhedron();
    }
    Polyhedron p = std::move(this->Pool.back());
    this->Pool.pop_back();
    return p;
  }
  void Release(Polyhedron& p) { this->Pool.push_back(std::move(p)); }

  const std::vector<BoxGeometry>& Geometry;
  double Tol;
  std::vector<Node>& Nodes;
  std::vector<Fragment>& Fragments;
  std::vector<Polyhedron> Pool;
  ClipScratch Scratch;
};

int Builder::Build(const dvec3& lo, const dvec3& hi)
{
  Polyhedron root = this->Acquire();
  MakeAxisBox(lo, hi, root);
  // Each box's part of the root, clipped plane by plane: exact where a corner test is not.
  std::vector<Partial> partial;
  Polyhedron scratch = this->Acquire();
  for (size_t b = 0; b < this->Geometry.size(); ++b)
  {
    Partial q{ static_cast<int>(b), this->Acquire() };
    q.Part = root;
    bool missed = false;
    for (const dvec4& plane : this->Geometry[b].Planes)
    {
      const Side s = Classify(q.Part, plane, this->Tol);
      missed = s == Side::Outside;
      if (missed)
      {
        break;
      }
      if (s == Side::Cut)
      {
        Clip(q.Part, plane, this->Tol, scratch, this->Scratch);
        std::swap(q.Part, scratch);
      }
    }
    if (missed)
    {
      this->Release(q.Part);
    }
    else
    {
      partial.push_back(std::move(q));
    }
  }
  this->Release(scratch);
  return this->Split(std::move(root), {}, std::move(partial), 0);
}

int Builder::Split(Polyhedron cell,
  std::vector<int> covering,
  std::vector<Partial> partial,
  int depth)
{
  this->Depth = std::max(this->Depth, depth);

  // Against the cell's own points each box misses it (outside one plane), covers it (inside all
  // six) or has a plane cutting it, which is then a split candidate.
  size_t kept = 0;
  for (Partial& q : partial)
  {
    bool missed = false;
    q.Cuts = 0;
    for (int f = 0; f < 6 && !missed; ++f)
    {
      const Side s = Classify(cell, this->Geometry[q.Box].Planes[f], this->Tol);
      missed = s == Side::Outside;
      q.Cuts |= s == Side::Cut ? 1 << f : 0;
    }
    if (missed || q.Cuts == 0)
    {
      if (!missed)
      {
        covering.push_back(q.Box);
      }
      this->Release(q.Part);
      continue;
    }
    if (&partial[kept] != &q)
    {
      partial[kept] = std::move(q);
    }
    ++kept;
  }
  partial.resize(kept);
  if (partial.empty())
  {
    const int leaf = this->MakeLeaf(cell, covering);
    this->Release(cell);
    return leaf;
  }

  // Cost of a candidate: the other partial boxes it cuts inside the cell (each may add a
  // fragment); covering boxes are cut by every candidate alike and do not count.
  int bestStraddles = std::numeric_limits<int>::max();
  bool bestTrims = false;
  dvec4 best(0.0);
  for (const Partial& p : partial)
  {
    for (int f = 0; f < 6; ++f)
    {
      if (!(p.Cuts & (1 << f)))
      {
        continue;
      }
      const dvec4& plane = this->Geometry[p.Box].Planes[f];
      int straddles = 0;
      bool trims = covering.empty(); // nothing outside the plane: a free cut
      for (const Partial& q : partial)
      {
        if (&q == &p)
        {
          continue;
        }
        const Side s = Classify(q.Part, plane, this->Tol);
        straddles += s == Side::Cut ? 1 : 0;
        trims = trims && s == Side::Inside;
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
  // Every split takes a plane out of the set cutting the cell, so the depth is bounded by the
  // plane count; this guard only stops rounding gone wrong, keeping the union covered.
  if (depth > 6 * static_cast<int>(this->Geometry.size()) + 8)
  {
    for (Partial& q : partial)
    {
      covering.push_back(q.Box);
      this->Release(q.Part);
    }
    const int leaf = this->MakeLeaf(cell, covering);
    this->Release(cell);
    return leaf;
  }

  std::vector<Partial> inside;
  std::vector<Partial> outside;
  for (Partial& q : partial)
  {
    const Side s = Classify(q.Part, best, this->Tol);
    if (s == Side::Inside)
    {
      inside.push_back(std::move(q));
    }
    else if (s == Side::Outside)
    {
      outside.push_back(std::move(q));
    }
    else
    {
      Partial in{ q.Box, this->Acquire() };
      Partial out{ q.Box, this->Acquire() };
      Clip(q.Part, best, this->Tol, in.Part, this->Scratch);
      Clip(q.Part, -best, this->Tol, out.Part, this->Scratch);
      this->Release(q.Part);
      inside.push_back(std::move(in));
      outside.push_back(std::move(out));
    }
  }
  partial.clear();
  Polyhedron in = this->Acquire();
  Polyhedron out = this->Acquire();
  Clip(cell, best, this->Tol, in, this->Scratch);
  Clip(cell, -best, this->Tol, out, this->Scratch);
  this->Release(cell);

  const int node = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes[node].Split = ToPlane(best);
  const int inChild = this->Split(std::move(in), covering, std::move(inside), depth + 1);
  const int outChild =
    this->Split(std::move(out), std::move(covering), std::move(outside), depth + 1);
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

  // Points closer than tol (two cuts just either side of a corner) become one vertex.
  std::vector<int> merged(cell.Points.size());
  std::vector<dvec3> vertices;
  for (size_t i = 0; i < cell.Points.size(); ++i)
  {
    const dvec3& p = cell.Points[i];
    merged[i] = -1;
    for (size_t k = 0; k < vertices.size() && merged[i] < 0; ++k)
    {
      const dvec3 e = p - vertices[k];
      merged[i] = glm::dot(e, e) <= this->Tol * this->Tol ? static_cast<int>(k) : -1;
    }
    if (merged[i] < 0)
    {
      merged[i] = static_cast<int>(vertices.size());
      vertices.push_back(p);
    }
  }
  for (size_t face = 0; face < cell.Planes.size(); ++face)
  {
    std::vector<int> loop;
    for (int k = cell.Offsets[face]; k < cell.Offsets[face + 1]; ++k)
    {
      const int index = merged[cell.Loops[k]];
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
    f.Planes.push_back(ToPlane(cell.Planes[face]));
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

bool VolumeBSPTree::SetBoxes(const std::vector<Box>& boxes)
{
  if (boxes == this->Boxes)
  {
    return false;
  }
  this->Boxes = boxes;
  this->NeedsBuild = true;
  return true;
}

void VolumeBSPTree::SetRelativeTolerance(double tolerance)
{
  if (tolerance != this->RelativeTolerance)
  {
    this->RelativeTolerance = tolerance;
    this->NeedsBuild = true;
  }
}

bool VolumeBSPTree::Update()
{
  if (!this->NeedsBuild)
  {
    return false;
  }
  this->Build();
  return true;
}

void VolumeBSPTree::Build()
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
  Builder builder(geometry, tol, this->Nodes, this->Fragments);
  this->Root = builder.Build(lo - pad, hi + pad);
  this->Depth = builder.Depth;
}

int VolumeBSPTree::GetMaximumOverlap() const
{
  size_t m = 0;
  for (const Fragment& f : this->Fragments)
  {
    m = std::max(m, f.VolumeIds.size());
  }
  return static_cast<int>(m);
}

int VolumeBSPTree::FindFragment(const Vector3& worldPoint) const
{
  const dvec3 p(worldPoint[0] - this->Origin[0],
    worldPoint[1] - this->Origin[1],
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

bool VolumeBSPTree::FragmentContainsPoint(int i, const Vector3& worldPoint) const
{
  const dvec3 p(worldPoint[0] - this->Origin[0],
    worldPoint[1] - this->Origin[1],
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

void VolumeBSPTree::Collect(int node,
  const Vector3& localEye,
  bool parallel,
  const Vector3& direction,
  std::vector<int>& order) const
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
  const bool insideFirst =
    parallel ? s[0] * direction[0] + s[1] * direction[1] + s[2] * direction[2] >= 0.0
             : s[0] * localEye[0] + s[1] * localEye[1] + s[2] * localEye[2] + s[3] <= 0.0;
  this->Collect(insideFirst ? n.Inside : n.Outside, localEye, parallel, direction, order);
  this->Collect(insideFirst ? n.Outside : n.Inside, localEye, parallel, direction, order);
}

void VolumeBSPTree::SortFrontToBack(const Vector3& eye,
  bool parallel,
  const Vector3& direction,
  std::vector<int>& order) const
{
  order.clear();
  order.reserve(this->Fragments.size());
  const Vector3 local = {
    { eye[0] - this->Origin[0], eye[1] - this->Origin[1], eye[2] - this->Origin[2] }
  };
  this->Collect(this->Root, local, parallel, direction, order);
}

void VolumeBSPTree::SortBackToFront(const Vector3& eye,
  bool parallel,
  const Vector3& direction,
  std::vector<int>& order) const
{
  this->SortFrontToBack(eye, parallel, direction, order);
  std::reverse(order.begin(), order.end());
}
}
