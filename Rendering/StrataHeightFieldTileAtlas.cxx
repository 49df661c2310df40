// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldTileAtlas.h"

#include "StrataRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include "vtkStackedHeightFieldPagedCorners.h"
#include "vtkStackedHeightFieldPagedLookup.h"
#include "vtkStackedHeightFieldPagedSearch.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace strata
{

std::string HeightFieldTileAtlas::GetLookupDeclarations()
{
  return vtkStackedHeightFieldPagedLookup;
}

std::string HeightFieldTileAtlas::GetCellCornersFunction()
{
  return vtkStackedHeightFieldPagedCorners;
}

std::string HeightFieldTileAtlas::GetSearchLevelCode()
{
  return vtkStackedHeightFieldPagedSearch;
}

int HeightFieldTileAtlas::Allocate(double budgetMiB, int pageSize, std::string& error)
{
  const int B = pageSize;
  GLint maxLayers = 0, maxSize = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const double tileBytes = double(B) * B * sizeof(float);
  const int slots =
    static_cast<int>(std::min<double>(maxLayers, std::floor(budgetMiB * 1048576.0 / tileBytes)));
  std::ostringstream msg;
  if (slots < 1 || B > maxSize)
  {
    msg << "An atlas of " << budgetMiB << " MiB holds no tile of " << B << " x " << B
        << " heights: raise AtlasBudget.";
    error = msg.str();
    return -1;
  }
  if (slots == this->Slots && B == this->PageSize && this->Atlas)
    return 0;
  glBindTexture(GL_TEXTURE_2D_ARRAY, this->Atlas.Get());
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, B, B, slots, 0, GL_RED, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  if (glGetError() != GL_NO_ERROR)
  {
    msg << "Could not allocate a tile atlas of " << slots << " tiles of " << B << " x " << B
        << " (out of GPU memory?): lower AtlasBudget.";
    error = msg.str();
    return -1;
  }
  this->Slots = slots;
  this->PageSize = B;
  return 1;
}

long long HeightFieldTileAtlas::Upload(const strata::HeightFieldPager& pager,
  const std::vector<strata::HeightFieldPager::Upload>& uploads)
{
  const int B = this->PageSize;
  long long bytes = 0;
  std::vector<float> values;
  if (!uploads.empty())
  {
    glBindTexture(GL_TEXTURE_2D_ARRAY, this->Atlas.GetName());
    const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 4);
    for (const auto& u : uploads)
    {
      pager.GetUploadValues(u, values);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, B, B, 1, GL_RED, GL_FLOAT, values.data());
      bytes += static_cast<long long>(values.size() * sizeof(float));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
  // Borders stitched anew to coarser neighbours: two columns and two rows per page.
  if (!pager.GetBorderUploads().empty())
  {
    glBindTexture(GL_TEXTURE_2D_ARRAY, this->Atlas.GetName());
    const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 4);
    for (const auto& u : pager.GetBorderUploads())
    {
      if (u.Slot < 0)
        continue;
      pager.GetBorderValues(u, values);
      const float* v = values.data();
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, 1, B, 1, GL_RED, GL_FLOAT, v);
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, B - 1, 0, u.Slot, 1, B, 1, GL_RED, GL_FLOAT, v + B);
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, B, 1, 1, GL_RED, GL_FLOAT, v + 2 * B);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, B - 1, u.Slot, B, 1, 1, GL_RED, GL_FLOAT, v + 3 * B);
      bytes += static_cast<long long>(values.size() * sizeof(float));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
  return bytes;
}

void HeightFieldTileAtlas::UploadPageTable(const strata::HeightFieldPager& pager)
{
  const std::vector<uint16_t>& table = pager.GetPageTable();
  const int* tiles = pager.GetTiles();
  glBindTexture(GL_TEXTURE_2D_ARRAY, this->PageTable.Get());
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 2);
  glTexImage3D(GL_TEXTURE_2D_ARRAY,
    0,
    GL_RGBA16UI,
    tiles[0],
    tiles[1],
    pager.GetNumberOfHorizons(),
    0,
    GL_RGBA_INTEGER,
    GL_UNSIGNED_SHORT,
    table.data());
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

void HeightFieldTileAtlas::Bind(vtkOpenGLRenderWindow* window,
  vtkShaderProgram* program,
  const strata::HeightFieldPager& pager)
{
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  vtkOpenGLState* state = window->GetState();
  this->Units[0] = units->Allocate();
  this->Units[1] = units->Allocate();
  state->vtkglActiveTexture(GL_TEXTURE0 + this->Units[0]);
  glBindTexture(GL_TEXTURE_2D_ARRAY, this->Atlas.GetName());
  program->SetUniformi("uAtlas", this->Units[0]);
  state->vtkglActiveTexture(GL_TEXTURE0 + this->Units[1]);
  glBindTexture(GL_TEXTURE_2D_ARRAY, this->PageTable.GetName());
  program->SetUniformi("uPageTable", this->Units[1]);
  program->SetUniformi("uPageStride", pager.GetPageSize() - 1);
  const int* tiles = pager.GetTiles();
  glUniform2i(program->FindUniform("uPageTiles"), tiles[0], tiles[1]);
}

void HeightFieldTileAtlas::Unbind(vtkOpenGLRenderWindow* window)
{
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  for (int& unit : this->Units)
  {
    if (unit < 0)
      continue;
    window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    units->Free(unit);
    unit = -1;
  }
}

void HeightFieldTileAtlas::ReleaseGraphicsResources()
{
  this->Atlas.Release();
  this->PageTable.Release();
  this->Slots = 0;
  this->PageSize = 0;
}
}
