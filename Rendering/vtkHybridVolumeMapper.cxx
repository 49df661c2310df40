// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHybridVolumeMapper.h"

#include "StrataGLObject.h"
#include "StrataGraphicsResources.h"
#include "StrataRenderUtilities.h"
#include "StrataShaderCache.h"
#include "StrataTransferFunctionTable.h"
#include "vtkMultiVolumeRayCastMapper.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPagePoolProtocol.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkHybridPointsFS.h"
#include "vtkHybridPointsShadeDec.h"
#include "vtkHybridPointsShadeImpl.h"
#include "vtkHybridPointsSplatFS.h"
#include "vtkHybridPointsSplatVS.h"
#include "vtkHybridPointsVS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace
{
using PointKey = std::pair<bool, bool>; ///< (Gaussian splats, shaded): all a point program uses

void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  strata::ShaderCache<PointKey>::Replace(source, tag, code);
}

// The point shaders for one shape, with or without shading: nothing else is compiled.
void BuildPointShaders(const PointKey& key, std::string& vs, std::string& fs)
{
  const bool splats = key.first, shaded = key.second;
  vs = vtkHybridPointsVS;
  fs = vtkHybridPointsFS;
  Replace(vs, "//STRATA::Splat::VSDec", splats ? "out float vSigma;\nout float vSide;" : "");
  // Every output written on every path, the culled points' too.
  Replace(vs, "//STRATA::Splat::VSCulled", splats ? "vSigma = 1.0;\n    vSide = 1.0;" : "");
  Replace(vs,
    "//STRATA::Splat::VSImpl",
    splats ? vtkHybridPointsSplatVS
           : "float side = max(ceil(size), 1.0);\n"
             "  gl_PointSize = side;\n"
             "  vColor = vec4(c, a) * min(size * size / (side * side), 1.0);");
  Replace(fs, "//STRATA::Splat::FSDec", splats ? "in float vSigma;\nin float vSide;" : "");
  Replace(
    fs, "//STRATA::Splat::FSImpl", splats ? vtkHybridPointsSplatFS : "gl_FragData[0] = vColor;");
  Replace(vs, "//STRATA::Normal::Dec", shaded ? vtkHybridPointsShadeDec : "");
  Replace(vs, "//STRATA::Normal::Impl", shaded ? vtkHybridPointsShadeImpl : "");
}

// Points sorted far to near by depth along the view direction, in S slabs of SubBuckets
// buckets each (a counting sort): slab s (0 nearest) is order[start[(S - 1 - s) * SubBuckets]
// .. start[(S - s) * SubBuckets]). Points of depth NaN are left out.
constexpr int SubBuckets = 64;
void SortPoints(const std::vector<double>& depth,
  double lo,
  double width,
  int S,
  std::vector<unsigned int>& order,
  std::vector<size_t>& start)
{
  const int buckets = S * SubBuckets;
  const size_t count = depth.size();
  std::vector<unsigned int> bucketOf(count);
  start.assign(buckets + 1, 0);
  for (size_t i = 0; i < count; ++i)
  {
    if (std::isnan(depth[i]))
    {
      bucketOf[i] = static_cast<unsigned int>(buckets); // outside the region: not drawn
      continue;
    }
    const int nearToFar =
      std::min(buckets - 1, std::max(0, int((depth[i] - lo) / width * buckets)));
    bucketOf[i] = static_cast<unsigned int>(buckets - 1 - nearToFar);
    ++start[bucketOf[i] + 1];
  }
  for (int k = 0; k < buckets; ++k)
    start[k + 1] += start[k];
  order.resize(start[buckets]);
  std::vector<size_t> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < count; ++i)
    if (bucketOf[i] < static_cast<unsigned int>(buckets))
      order[fill[bucketOf[i]]++] = static_cast<unsigned int>(i);
}
}

class vtkHybridVolumeMapper::vtkInternals
{
public:
  using Self = vtkHybridVolumeMapper;
  explicit vtkInternals(Self* self)
    : GraphicsResources(self, &Self::ReleaseGraphicsResources)
  {
  }

  strata::GraphicsResources<Self> GraphicsResources;
  vtkNew<vtkMultiVolumeRayCastMapper> Volume;
  vtkNew<vtkPlaneCollection> Slab;
  vtkNew<vtkPlane> Near;
  vtkNew<vtkPlane> Far;

  // Points on the GPU: position relative to Origin (float keeps UTM-scale scenes precise),
  // value, error, normal.
  vtkPolyData* PointsInput = nullptr;
  vtkMTimeType PointsTime = 0;
  std::array<double, 3> Origin = { 0, 0, 0 };
  std::vector<double> Positions; // double, relative to Origin, for the per-frame depth sort
  bool HasNormals = false;
  strata::GLObject VBO{ strata::GLObject::Kinds::Buffer };
  strata::GLObject IBO{ strata::GLObject::Kinds::Buffer };
  strata::GLObject VAO{ strata::GLObject::Kinds::VertexArray };
  vtkShaderProgram* VaoProgram = nullptr;
  vtkIdType Count = 0;
  vtkIdType Drawn = 0;

  strata::TransferFunctionTable Transfer; ///< the volume property's table, as the ray caster's
  strata::ShaderCache<PointKey> Programs;
  PointKey LastKey{ false, false };

  /// What a frame draws with: the points sorted into slabs, the depths they span, the
  /// projection of a cell and the program's key.
  struct Frame
  {
    double Lo = 1e300, Hi = -1e300;
    std::vector<unsigned int> Order;
    std::vector<size_t> Start;
    double Cell = 0.0;
    bool Shaded = false;
    PointKey Key{ false, false };
    float LocalToClip[16];
    vtkNew<vtkMatrix4x4> Linear; ///< the prop's linear part
    double Scale = 1.0;          ///< cube root of its |determinant|
    double PixelsPerUnit = 0.0;
    double Eye[3], Direction[3];
  };

  void UploadPoints(vtkPolyData* points,
    vtkDataArray* values,
    vtkDataArray* errors,
    vtkDataArray* normals,
    vtkIdType count);
  void Sort(Self* self, vtkRenderer* ren, vtkVolume* vol, Frame& frame);
  vtkShaderProgram* ReadyPoints(vtkOpenGLRenderWindow* renWin, Frame& frame, bool first);
  void SetUniforms(vtkRenderer* ren, vtkVolume* vol, vtkShaderProgram* program, Frame& frame);
  void DrawSlabPoints(vtkOpenGLRenderWindow* renWin, size_t first, size_t last);
  void SetSlabPlanes(vtkPlaneCollection* planes,
    const Frame& frame,
    int s,
    int S,
    vtkPlaneCollection* slab);
  void SetUpProjection(vtkRenderer* ren, vtkVolume* vol, Frame& frame);

  void Release(vtkWindow* window)
  {
    this->VBO.Release();
    this->IBO.Release();
    this->VAO.Release();
    this->VaoProgram = nullptr;
    this->PointsInput = nullptr;
    this->PointsTime = 0;
    this->Transfer.ReleaseGraphicsResources(window);
    this->Programs.ReleaseGraphicsResources();
  }
};

// --- Points: uploaded when they change (position relative to their centre, value, error and,
// shaded, normal).
void vtkHybridVolumeMapper::vtkInternals::UploadPoints(vtkPolyData* points,
  vtkDataArray* values,
  vtkDataArray* errors,
  vtkDataArray* normals,
  vtkIdType count)
{
  const bool shaded = normals != nullptr;
  if (this->PointsInput == points && this->PointsTime >= points->GetMTime() &&
      this->Count == count && this->HasNormals == shaded)
    return;
  double b[6];
  points->GetBounds(b);
  this->Origin = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const int stride = shaded ? 8 : 5;
  std::vector<float> vbo(size_t(count) * stride);
  this->Positions.resize(3 * size_t(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    float* v = &vbo[size_t(i) * stride];
    for (int c = 0; c < 3; ++c)
    {
      this->Positions[3 * size_t(i) + c] = p[c] - this->Origin[c];
      v[c] = static_cast<float>(p[c] - this->Origin[c]);
    }
    v[3] = static_cast<float>(values->GetComponent(i, 0));
    v[4] = static_cast<float>(errors->GetComponent(i, 0));
    for (int c = 0; shaded && c < 3; ++c)
      v[5 + c] = static_cast<float>(normals->GetComponent(i, c));
  }
  glBindBuffer(GL_ARRAY_BUFFER, this->VBO.Get());
  glBufferData(GL_ARRAY_BUFFER, vbo.size() * sizeof(float), vbo.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  this->PointsInput = points;
  this->PointsTime = points->GetMTime();
  this->Count = count;
  this->HasNormals = shaded;
  this->VaoProgram = nullptr;
}

// --- Slabs: depth along the view direction over the volume's and the points' extent, and
// the points sorted into them far to near.
void vtkHybridVolumeMapper::vtkInternals::Sort(Self* self,
  vtkRenderer* ren,
  vtkVolume* vol,
  Frame& frame)
{
  vtkCamera* camera = ren->GetActiveCamera();
  camera->GetPosition(frame.Eye);
  camera->GetDirectionOfProjection(frame.Direction);
  const double* eye = frame.Eye;
  const double* dir = frame.Direction;
  const double* m = vol->GetMatrix()->GetData();
  const double* vb = vol->GetBounds();
  for (int k = 0; k < 8; ++k)
  {
    const double corner[3] = { vb[k & 1], vb[2 + ((k >> 1) & 1)], vb[4 + ((k >> 2) & 1)] };
    double d = 0.0;
    for (int c = 0; c < 3; ++c)
      d += (corner[c] - eye[c]) * dir[c];
    frame.Lo = std::min(frame.Lo, d);
    frame.Hi = std::max(frame.Hi, d);
  }
  std::vector<double> depth(static_cast<size_t>(this->Count));
  double region[6];
  const double* box = this->Volume->GetRegion(region) ? region : nullptr;
  for (vtkIdType i = 0; i < this->Count; ++i)
  {
    // local (relative to the points' origin) -> world by the prop's matrix -> depth.
    const double* local = &this->Positions[3 * size_t(i)];
    double d = 0.0;
    bool outside = false;
    for (int r = 0; r < 3; ++r)
    {
      double w = m[4 * r + 3];
      for (int c = 0; c < 3; ++c)
        w += m[4 * r + c] * (local[c] + this->Origin[c]);
      d += (w - eye[r]) * dir[r];
      // (Half open, lo <= w < hi: boxes sharing a face draw a point on it once.)
      outside = outside || (box && (w < box[2 * r] || w >= box[2 * r + 1]));
    }
    if (outside)
    {
      depth[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    depth[i] = d;
    frame.Lo = std::min(frame.Lo, d);
    frame.Hi = std::max(frame.Hi, d);
  }
  SortPoints(depth,
    frame.Lo,
    std::max(frame.Hi - frame.Lo, 1e-300),
    self->NumberOfSlabs,
    frame.Order,
    frame.Start);
}

// The point program (bound, its vertex array set up for it); the first slab of a frame also
// uploads the frame's point order and sets the uniforms.
vtkShaderProgram* vtkHybridVolumeMapper::vtkInternals::ReadyPoints(vtkOpenGLRenderWindow* renWin,
  Frame& frame,
  bool first)
{
  vtkShaderProgram* program = this->Programs.Ready(renWin,
    frame.Key,
    [](const PointKey& key, std::string& vs, std::string& fs) { BuildPointShaders(key, vs, fs); });
  if (!program)
    return nullptr;
  this->LastKey = frame.Key;
  glBindVertexArray(this->VAO.Get());
  if (!first)
    return program;
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, this->IBO.Get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
    frame.Order.size() * sizeof(unsigned int),
    frame.Order.data(),
    GL_STREAM_DRAW);
  if (this->VaoProgram != program)
  {
    glBindBuffer(GL_ARRAY_BUFFER, this->VBO.GetName());
    const GLsizei stride = (frame.Shaded ? 8 : 5) * sizeof(float);
    auto attribute = [&](const char* name, int size, size_t offset)
    {
      const GLint location = glGetAttribLocation(program->GetHandle(), name);
      if (location >= 0)
      {
        glEnableVertexAttribArray(location);
        glVertexAttribPointer(location,
          size,
          GL_FLOAT,
          GL_FALSE,
          stride,
          reinterpret_cast<const void*>(offset * sizeof(float)));
      }
    };
    attribute("vertexLocal", 3, 0);
    attribute("pointValue", 1, 3);
    attribute("pointError", 1, 4);
    if (frame.Shaded)
      attribute("pointNormal", 3, 5);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    this->VaoProgram = program;
  }
  return program;
}

// The frame's point uniforms: projection, cell size in pixels, the transfer table and, shaded,
// the lights and material.
void vtkHybridVolumeMapper::vtkInternals::SetUniforms(vtkRenderer* ren,
  vtkVolume* vol,
  vtkShaderProgram* program,
  Frame& frame)
{
  int vp[4];
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  program->SetUniformMatrix4x4("uLocalToClip", frame.LocalToClip);
  program->SetUniformf("uCellSize", static_cast<float>(frame.Cell * frame.Scale));
  program->SetUniformf("uPixelsPerUnit", static_cast<float>(frame.PixelsPerUnit * vp[3] / 2.0));
  const double* r = this->Transfer.GetTableRange();
  const float range[3] = { float(r[0]), float(r[1]), float(r[2]) };
  program->SetUniform3f("uTableRange", range);
  if (!frame.Shaded)
    return;
  std::vector<float> lightDirections, lightColors;
  strata::RenderUtilities::GetLights(ren, lightDirections, lightColors);
  program->SetUniformi("uNumLights", static_cast<int>(lightDirections.size() / 3));
  if (!lightDirections.empty())
  {
    program->SetUniform3fv("uLightDirection",
      static_cast<int>(lightDirections.size() / 3),
      reinterpret_cast<const float(*)[3]>(lightDirections.data()));
    program->SetUniform3fv("uLightColor",
      static_cast<int>(lightColors.size() / 3),
      reinterpret_cast<const float(*)[3]>(lightColors.data()));
  }
  // Normals go to world by the inverse transpose of the prop's linear part.
  vtkNew<vtkMatrix4x4> inv;
  vtkMatrix4x4::Invert(frame.Linear, inv);
  float n3[9];
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c)
      n3[3 * c + i] = static_cast<float>(inv->GetElement(c, i)); // column-major transpose
  program->SetUniformMatrix3x3("uNormalToWorld", n3);
  vtkVolumeProperty* property = vol->GetProperty();
  const float material[4] = { float(property->GetAmbient(0)),
    float(property->GetDiffuse(0)),
    float(property->GetSpecular(0)),
    float(property->GetSpecularPower(0)) };
  program->SetUniform4f("uMaterial", material);
  const float view[3] = {
    float(-frame.Direction[0]), float(-frame.Direction[1]), float(-frame.Direction[2])
  };
  program->SetUniform3f("uViewDirection", view);
}

// The points of one slab, far to near, blended over it (premultiplied), depth-tested against
// the scene but not written.
void vtkHybridVolumeMapper::vtkInternals::DrawSlabPoints(vtkOpenGLRenderWindow* renWin,
  size_t first,
  size_t last)
{
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  const strata::RenderUtilities::ScopedEnable pointSize(GL_PROGRAM_POINT_SIZE);
  glDrawElements(GL_POINTS,
    static_cast<GLsizei>(last - first),
    GL_UNSIGNED_INT,
    reinterpret_cast<const void*>(first * sizeof(unsigned int)));
  glBindVertexArray(0);
  this->Drawn += static_cast<vtkIdType>(last - first);
}

// Slab s of S: the volume between depths lo + s w / S and lo + (s + 1) w / S; the nearest
// slab is open towards the eye and the farthest away from it; the user's planes too.
void vtkHybridVolumeMapper::vtkInternals::SetSlabPlanes(vtkPlaneCollection* planes,
  const Frame& frame,
  int s,
  int S,
  vtkPlaneCollection* slab)
{
  const double* eye = frame.Eye;
  const double* dir = frame.Direction;
  for (int i = 0; i < planes->GetNumberOfItems(); ++i)
    slab->AddItem(planes->GetItem(i));
  const double width = std::max(frame.Hi - frame.Lo, 1e-300);
  const double d0 = frame.Lo + width * s / S, d1 = frame.Lo + width * (s + 1) / S;
  if (s > 0)
  {
    this->Near->SetOrigin(eye[0] + d0 * dir[0], eye[1] + d0 * dir[1], eye[2] + d0 * dir[2]);
    this->Near->SetNormal(frame.Direction);
    slab->AddItem(this->Near);
  }
  if (s < S - 1)
  {
    this->Far->SetOrigin(eye[0] + d1 * dir[0], eye[1] + d1 * dir[1], eye[2] + d1 * dir[2]);
    this->Far->SetNormal(-dir[0], -dir[1], -dir[2]);
    slab->AddItem(this->Far);
  }
}

vtkStandardNewMacro(vtkHybridVolumeMapper);

vtkHybridVolumeMapper::vtkHybridVolumeMapper()
  : Internals(new vtkInternals(this))
{
  this->SetNumberOfInputPorts(2);
  this->Internals->Slab->AddItem(this->Internals->Near);
  this->Internals->Slab->AddItem(this->Internals->Far);
}

vtkHybridVolumeMapper::~vtkHybridVolumeMapper()
{
  // GL names die in their own context: the callback makes it current if the window lives.
  this->Internals->GraphicsResources.Release();
}

int vtkHybridVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkTypeBool vtkHybridVolumeMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the input (GetBounds, the render), a pool's reader serves its coarsest
  // level only: the bricks are paged by the volume mapper.
  vtkPagePoolProtocol::RequestCoarsestLevels(request, inputVector, 1);
  return result;
}

void vtkHybridVolumeMapper::SetPointShape(PointShapes shape)
{
  if (this->PointShape != shape)
  {
    this->PointShape = shape;
    this->Modified();
  }
}

void vtkHybridVolumeMapper::SetPointsInputData(vtkPolyData* points)
{
  this->SetInputDataInternal(1, points);
}

void vtkHybridVolumeMapper::SetPointsInputConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

// The region is the ray caster's (one box for the volume and the points).
void vtkHybridVolumeMapper::SetRegion(const double bounds[6])
{
  double current[6];
  if (this->Internals->Volume->GetRegion(current) && std::equal(bounds, bounds + 6, current))
    return;
  this->Internals->Volume->SetRegion(bounds);
  this->Modified();
}

void vtkHybridVolumeMapper::RemoveRegion()
{
  double current[6];
  if (!this->Internals->Volume->GetRegion(current))
    return;
  this->Internals->Volume->RemoveRegion();
  this->Modified();
}

bool vtkHybridVolumeMapper::GetRegion(double bounds[6]) const
{
  return this->Internals->Volume->GetRegion(bounds);
}

vtkMultiVolumeRayCastMapper* vtkHybridVolumeMapper::GetVolumeMapper()
{
  return this->Internals->Volume;
}

vtkIdType vtkHybridVolumeMapper::GetNumberOfPointsDrawn() const
{
  return this->Internals->Drawn;
}

std::string vtkHybridVolumeMapper::GetPointVertexShaderSource() const
{
  const auto* entry = this->Internals->Programs.Find(this->Internals->LastKey);
  return entry ? entry->Vertex : std::string();
}

std::string vtkHybridVolumeMapper::GetPointFragmentShaderSource() const
{
  const auto* entry = this->Internals->Programs.Find(this->Internals->LastKey);
  return entry ? entry->Fragment : std::string();
}

int vtkHybridVolumeMapper::GetNumberOfShaderSourcesBuilt() const
{
  return this->Internals->Programs.GetSourcesBuilt();
}

int vtkHybridVolumeMapper::GetNumberOfShaderCompilations() const
{
  return this->Internals->Programs.GetCompilations();
}

void vtkHybridVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
  this->Internals->Volume->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

// The inputs of a frame: a page pool behind input 0 is paged by the volume mapper from the
// reader's output port; otherwise the low-resolution image is its input.
vtkImageData* vtkHybridVolumeMapper::UpdateInputs(vtkPolyData*& points)
{
  vtkInternals& in = *this->Internals;
  for (int port = 0; port < 2; ++port)
  {
    if (this->GetNumberOfInputConnections(port) == 0)
      continue;
    this->GetInputAlgorithm(port, 0)->UpdateInformation();
    vtkPagePoolProtocol::RequestCoarsestLevel(this->GetInputInformation(port, 0));
    this->GetInputAlgorithm(port, 0)->Update();
  }
  auto* low = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  points = this->GetNumberOfInputConnections(1) > 0
             ? vtkPolyData::SafeDownCast(this->GetInputDataObject(1, 0))
             : nullptr;
  if (!low)
  {
    vtkErrorMacro("No low-resolution volume on input 0.");
    return nullptr;
  }
  if (vtkPagePoolProtocol::GetInputPool(this->GetInputInformation(0, 0), low).IsValid())
  {
    if (in.Volume->GetInputConnection(0, 0) != this->GetInputConnection(0, 0))
      in.Volume->SetInputConnection(this->GetInputConnection(0, 0));
  }
  else if (in.Volume->GetInput() != low)
  {
    in.Volume->SetInputData(low);
  }
  return low;
}

// The world size of the cell a point stands for: PointSpacing, or the geometric mean of the
// points' field data "PointSpacing"; 0 when there is neither.
double vtkHybridVolumeMapper::GetCellSize(vtkPolyData* points)
{
  if (this->PointSpacing > 0.0)
    return this->PointSpacing;
  vtkDataArray* spacing = points->GetFieldData()->GetArray("PointSpacing");
  if (!spacing || spacing->GetNumberOfTuples() * spacing->GetNumberOfComponents() < 3)
  {
    vtkErrorMacro(
      "No PointSpacing: set it, or give the points field data \"PointSpacing\" (3 values).");
    return 0.0;
  }
  double g[3];
  for (int c = 0; c < 3; ++c)
    g[c] = spacing->GetNumberOfComponents() >= 3 ? spacing->GetComponent(0, c)
                                                 : spacing->GetComponent(c, 0);
  return std::cbrt(std::abs(g[0] * g[1] * g[2]));
}

// One frame: the points uploaded and sorted into depth slabs; then, far to near, each slab of
// the volume ray cast (one cut for the whole frame) and the slab's points blended over it.
void vtkHybridVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkHybridVolumeMapper needs an OpenGL render window.");
    return;
  }
  in.GraphicsResources.Register(renWin);
  vtkPolyData* points = nullptr;
  if (!this->UpdateInputs(points))
    return;
  in.Volume->HoldCutOff();
  // The user's clipping planes apply to the volume and, through the slabs, to nothing else:
  // points are dropped by the depth sort only.
  vtkNew<vtkPlaneCollection> planes;
  for (int i = 0; this->ClippingPlanes && i < this->ClippingPlanes->GetNumberOfItems(); ++i)
    planes->AddItem(this->ClippingPlanes->GetItem(i));
  vtkDataArray* values = points ? points->GetPointData()->GetArray("Value") : nullptr;
  vtkDataArray* errors = points ? points->GetPointData()->GetArray("Error") : nullptr;
  const vtkIdType count = values && errors ? points->GetNumberOfPoints() : 0;
  if (points && count == 0 && points->GetNumberOfPoints() > 0)
    vtkErrorMacro(
      "The points input has no \"Value\" and \"Error\" point data: drawing the volume alone.");
  in.Drawn = 0;
  if (count == 0)
  {
    in.Volume->SetClippingPlanes(planes);
    in.Volume->Render(ren, vol);
    return;
  }
  vtkInternals::Frame frame;
  frame.Cell = this->GetCellSize(points);
  if (frame.Cell <= 0.0)
    return;
  vtkDataArray* normals = points->GetPointData()->GetArray("Normals");
  vtkVolumeProperty* property = vol->GetProperty();
  frame.Shaded = property->GetShade(0) != 0 && normals && normals->GetNumberOfComponents() == 3 &&
                 ren->GetLights()->GetNumberOfItems() > 0;
  frame.Key = { this->PointShape == PointShapes::GaussianSplats, frame.Shaded };
  in.UploadPoints(points, values, errors, frame.Shaded ? normals : nullptr, count);
  in.Transfer.Update(renWin, property);
  in.Sort(this, ren, vol, frame);
  in.SetUpProjection(ren, vol, frame);
  const int S = this->NumberOfSlabs;
  bool first = true;
  for (int s = S - 1; s >= 0; --s)
  {
    vtkNew<vtkPlaneCollection> slabPlanes;
    in.SetSlabPlanes(planes, frame, s, S, slabPlanes);
    in.Volume->SetClippingPlanes(slabPlanes);
    in.Volume->Render(ren, vol);
    in.Volume->HoldCutOn(); // one cut for the whole frame
    const size_t begin = frame.Start[size_t(S - 1 - s) * SubBuckets];
    const size_t end = frame.Start[size_t(S - s) * SubBuckets];
    if (end == begin)
      continue;
    vtkShaderProgram* program = in.ReadyPoints(renWin, frame, first);
    if (!program)
    {
      vtkErrorMacro("The hybrid point shader did not compile or link.");
      return;
    }
    if (first)
      in.SetUniforms(ren, vol, program, frame);
    first = false;
    in.Transfer.GetTexture()->Activate();
    program->SetUniformi("uTransfer", in.Transfer.GetTexture()->GetTextureUnit());
    in.DrawSlabPoints(renWin, begin, end);
    in.Transfer.GetTexture()->Deactivate();
  }
  in.Volume->SetClippingPlanes(planes);
}

// Projection: points relative to their origin to clip space by the prop's matrix; a cell of
// size g at clip w covers g * P11 * height / 2 / w pixels, times the prop's scale.
void vtkHybridVolumeMapper::vtkInternals::SetUpProjection(vtkRenderer* ren,
  vtkVolume* vol,
  Frame& frame)
{
  vtkInternals& in = *this;
  vtkCamera* camera = ren->GetActiveCamera();
  const double aspect = ren->GetTiledAspectRatio();
  vtkNew<vtkMatrix4x4> toLocal, localToClip, shift;
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  frame.PixelsPerUnit = camera->GetProjectionTransformMatrix(aspect, -1, 1)->GetElement(1, 1);
  toLocal->DeepCopy(vol->GetMatrix());
  for (int c = 0; c < 3; ++c)
    shift->SetElement(c, 3, in.Origin[c]);
  vtkMatrix4x4::Multiply4x4(toLocal, shift, toLocal);
  vtkMatrix4x4::Multiply4x4(worldToClip, toLocal, localToClip);
  strata::RenderUtilities::ToColumnMajor(localToClip->GetData(), frame.LocalToClip);
  frame.Linear->DeepCopy(vol->GetMatrix());
  for (int c = 0; c < 3; ++c)
    frame.Linear->SetElement(c, 3, 0.0);
  frame.Scale = std::cbrt(std::abs(frame.Linear->Determinant()));
}

void vtkHybridVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "PointShape: " << (this->PointShape == PointShapes::Squares ? "Squares" : "GaussianSplats")
     << "\n";
  os << indent << "NumberOfSlabs: " << this->NumberOfSlabs << "\n";
  os << indent << "PointSpacing: " << this->PointSpacing << "\n";
}
