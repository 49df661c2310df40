// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldTileAtlas
 * @brief   The GPU side of paged horizons: the tile atlas, the page table, and the GLSL that
 *          reads them.
 *
 * strata::HeightFieldPager decides which tile lives in which slot and writes the page table; this
 * object holds the textures: the atlas, an R32F 2-D array of B x B tiles (one layer a slot, as
 * many as AtlasBudget and the GPU's layer limit allow), and the page table, an RGBA16UI 2-D
 * array with one texel per level-0 tile and horizon (slot x, y, z, level). It uploads what
 * entered the atlas, the stitched borders that changed, and the table when the cut changed.
 * Following Tuvok's rule, the object that owns the page table writes the code that reads it:
 * the height lookup, the leaf's page and the corners of its cells (GetLookupDeclarations and
 * friends) are the only paged GLSL.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataHeightFieldTileAtlas_h
#define StrataHeightFieldTileAtlas_h

#include "StrataGLObject.h"         // For strata::GLObject
#include "StrataHeightFieldPager.h" // For strata::HeightFieldPager::Upload
#include "StrataRenderingModule.h"  // For export macro

#include <string> // For std::string
#include <vector> // For std::vector

class vtkOpenGLRenderWindow;
class vtkShaderProgram;

namespace strata
{
class STRATARENDERING_EXPORT HeightFieldTileAtlas
{
public:
  ///@{
  /// The paged GLSL: the height lookup (vtkStackedHeightFieldPagedLookup.glsl), the corners of
  /// a leaf's cell from its own tile, and the search's switch to the leaf's tile and level.
  static std::string GetLookupDeclarations();
  static std::string GetCellCornersFunction();
  static std::string GetSearchLevelCode();
  ///@}

  /**
   * Sizes the atlas for `budgetMiB` of B x B float tiles within the GPU's limits. Returns -1
   * with `error` set when it holds no tile or cannot be allocated, 1 when it was
   * (re)allocated (its contents are lost: the pager must upload everything again), else 0.
   */
  int Allocate(double budgetMiB, int pageSize, std::string& error);
  int GetSlots() const { return this->Slots; }

  /// Uploads the tiles that entered the atlas and the borders the pager stitched anew;
  /// returns the bytes uploaded.
  long long Upload(const strata::HeightFieldPager& pager,
    const std::vector<strata::HeightFieldPager::Upload>& uploads);
  /// Uploads the page table (tiles x tiles x horizons entries).
  void UploadPageTable(const strata::HeightFieldPager& pager);
  bool HasPageTable() const { return static_cast<bool>(this->PageTable); }

  /// Binds atlas and page table on two units of the window's manager and sets their uniforms.
  void Bind(vtkOpenGLRenderWindow* window,
    vtkShaderProgram* program,
    const strata::HeightFieldPager& pager);
  void Unbind(vtkOpenGLRenderWindow* window);

  void ReleaseGraphicsResources();

private:
  strata::GLObject Atlas{ strata::GLObject::Kinds::Texture };
  strata::GLObject PageTable{ strata::GLObject::Kinds::Texture };
  int Slots = 0;
  int PageSize = 0;
  int Units[2] = { -1, -1 };
};
}

#endif
