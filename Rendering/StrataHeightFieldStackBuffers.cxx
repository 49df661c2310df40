// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldStackBuffers.h"

#include "StrataHeightFieldStack.h"
#include "StrataMinMaxQuadtree.h"

#include "StrataRenderUtilities.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

namespace strata
{

namespace
{
void UploadBuffer(vtkOpenGLRenderWindow* window,
  vtkOpenGLBufferObject* bo,
  vtkTextureObject* tex,
  const std::vector<float>& data,
  int comps)
{
  tex->SetContext(window);
  bo->Upload(data, vtkOpenGLBufferObject::TextureBuffer);
  tex->CreateTextureBuffer(static_cast<unsigned int>(data.size() / comps), comps, VTK_FLOAT, bo);
}
}

HeightFieldStackBuffers::HeightFieldStackBuffers()
{
  for (auto* bo : { this->NodeBuffer.Get(),
         this->IntervalBuffer.Get(),
         this->LayerListBuffer.Get(),
         this->ColorBuffer.Get() })
  {
    bo->SetType(vtkOpenGLBufferObject::TextureBuffer);
  }
  this->BoxIndices->SetType(vtkOpenGLBufferObject::ElementArrayBuffer);
}

HeightFieldStackBuffers::~HeightFieldStackBuffers() = default;

namespace
{
// The layers of `stack` as one R32F 2-D array texture (NaN kept: it marks no data).
bool UploadLayers(vtkOpenGLRenderWindow* window,
  unsigned int texture,
  const strata::HeightFieldStack& stack,
  const char* what,
  std::string& error)
{
  const int nx = stack.GetNX(), ny = stack.GetNY(), layers = stack.GetNumberOfLayers();
  GLint maxSize = 0, maxLayers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (nx > maxSize || ny > maxSize || layers > maxLayers)
  {
    error = "A grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " x " +
            std::to_string(layers) + " " + what + " exceeds this GPU's texture limits (" +
            std::to_string(maxSize) + " per side, " + std::to_string(maxLayers) +
            " layers); page it from a tile pool instead.";
    return false;
  }
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  {
    const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, nx, ny, layers, 0, GL_RED, GL_FLOAT, nullptr);
    for (int k = 0; k < layers; ++k)
    {
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, k, nx, ny, 1, GL_RED, GL_FLOAT, stack.GetLayer(k));
    }
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  if (glGetError() != GL_NO_ERROR)
  {
    error = "Could not upload " + std::to_string(layers) + " " + what + " of " +
            std::to_string(nx) + " x " + std::to_string(ny) + " values (out of GPU memory?).";
    return false;
  }
  return true;
}
}

bool HeightFieldStackBuffers::UploadHeights(vtkOpenGLRenderWindow* window,
  const strata::HeightFieldStack& stack,
  std::string& error)
{
  return UploadLayers(window, this->Heights.Get(), stack, "horizons", error);
}

bool HeightFieldStackBuffers::UploadAttributes(vtkOpenGLRenderWindow* window,
  const strata::HeightFieldStack& attributes,
  std::string& error)
{
  if (attributes.GetNumberOfLayers() == 0)
  {
    this->Attributes.Release();
    return true;
  }
  return UploadLayers(window, this->Attributes.Get(), attributes, "attribute grids", error);
}

void HeightFieldStackBuffers::UploadTree(vtkOpenGLRenderWindow* window,
  const strata::MinMaxQuadtree& tree)
{
  std::vector<float> nodes, intervals, lists;
  for (const auto& node : tree.GetNodes())
  {
    // An empty node's range is (+Inf, -Inf) in the tree; the shader gets finite values of the
    // same order (min > max), so its test compares no Inf (fast math may assume there is none).
    const bool empty = !(node.Min <= node.Max);
    nodes.insert(nodes.end(),
      { empty ? 3.0e38f : node.Min,
        empty ? -3.0e38f : node.Max,
        float(node.IntervalOffset),
        float(node.IntervalCount) });
  }
  for (const auto& iv : tree.GetIntervals())
  {
    intervals.insert(
      intervals.end(), { iv.ZMin, iv.ZMax, float(iv.LayerOffset), float(iv.LayerCount) });
  }
  for (int id : tree.GetLayerLists())
  {
    lists.push_back(float(id));
  }
  if (intervals.empty())
    intervals.assign(4, 0.0f);
  if (lists.empty())
    lists.assign(1, 0.0f);
  UploadBuffer(window, this->NodeBuffer, this->NodeTexture, nodes, 4);
  UploadBuffer(window, this->IntervalBuffer, this->IntervalTexture, intervals, 4);
  UploadBuffer(window, this->LayerListBuffer, this->LayerListTexture, lists, 1);
}

void HeightFieldStackBuffers::UploadBox(int nx, int ny, const double valueRange[2])
{
  double zr[2] = { valueRange[0], valueRange[1] };
  if (zr[0] > zr[1])
  {
    zr[0] = zr[1] = 0.0;
  }
  const double pad = std::max(1e-3, 1e-3 * (zr[1] - zr[0]));
  const float x1 = float(nx - 1), y1 = float(ny - 1);
  const float z0 = float(zr[0] - pad), z1 = float(zr[1] + pad);
  const std::vector<float> verts = {
    0, 0, z0, x1, 0, z0, 0, y1, z0, x1, y1, z0, 0, 0, z1, x1, 0, z1, 0, y1, z1, x1, y1, z1
  };
  const std::vector<unsigned int> faces = { 0,
    2,
    1,
    1,
    2,
    3,
    4,
    5,
    6,
    5,
    7,
    6,
    0,
    1,
    4,
    1,
    5,
    4,
    2,
    6,
    3,
    3,
    6,
    7,
    0,
    4,
    2,
    2,
    4,
    6,
    1,
    3,
    5,
    3,
    7,
    5 };
  this->BoxVertices->Upload(verts, vtkOpenGLBufferObject::ArrayBuffer);
  this->BoxIndices->Upload(faces, vtkOpenGLBufferObject::ElementArrayBuffer);
  this->ArrayProgram = nullptr; // attribute bindings must be redone
}

void HeightFieldStackBuffers::UploadColors(vtkOpenGLRenderWindow* window,
  const std::vector<float>& colors)
{
  UploadBuffer(window, this->ColorBuffer, this->ColorTexture, colors, 4);
}

void HeightFieldStackBuffers::BindBox(vtkShaderProgram* program)
{
  if (program == this->ArrayProgram && this->BoxArray)
    return;
  // A plain vertex array: the box has one attribute, and its element buffer is part of its
  // state.
  glBindVertexArray(this->BoxArray.Get());
  this->BoxVertices->Bind();
  const GLint location = glGetAttribLocation(program->GetHandle(), "vertexGrid");
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  this->BoxIndices->Bind();
  glBindVertexArray(0);
  this->ArrayProgram = program;
}

void HeightFieldStackBuffers::DrawBox()
{
  glBindVertexArray(this->BoxArray.GetName());
  glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

void HeightFieldStackBuffers::Activate(vtkShaderProgram* program, bool colors)
{
  this->NodeTexture->Activate();
  program->SetUniformi("uNodes", this->NodeTexture->GetTextureUnit());
  this->IntervalTexture->Activate();
  program->SetUniformi("uIntervals", this->IntervalTexture->GetTextureUnit());
  this->LayerListTexture->Activate();
  program->SetUniformi("uLayerLists", this->LayerListTexture->GetTextureUnit());
  if (colors)
  {
    this->ColorTexture->Activate();
    program->SetUniformi("uColors", this->ColorTexture->GetTextureUnit());
  }
}

void HeightFieldStackBuffers::Deactivate(bool colors)
{
  this->NodeTexture->Deactivate();
  this->IntervalTexture->Deactivate();
  this->LayerListTexture->Deactivate();
  if (colors)
    this->ColorTexture->Deactivate();
}

void HeightFieldStackBuffers::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Heights.Release();
  this->Attributes.Release();
  for (auto* t : { this->NodeTexture.Get(),
         this->IntervalTexture.Get(),
         this->LayerListTexture.Get(),
         this->ColorTexture.Get() })
  {
    t->ReleaseGraphicsResources(window);
  }
  for (auto* b : { this->NodeBuffer.Get(),
         this->IntervalBuffer.Get(),
         this->LayerListBuffer.Get(),
         this->ColorBuffer.Get(),
         this->BoxVertices.Get(),
         this->BoxIndices.Get() })
  {
    b->ReleaseGraphicsResources();
  }
  this->BoxArray.Release();
  this->ArrayProgram = nullptr;
}
}
