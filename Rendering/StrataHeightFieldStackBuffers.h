// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldStackBuffers
 * @brief   What the stacked height-field ray caster draws with, on the GPU: the heights (in
 *          core), the min-max quadtree, the colours, and the proxy box whose back faces start
 *          the rays.
 *
 * In core the heights are one R32F 2-D array texture, one layer per horizon (paged, the tile
 * atlas holds them: strata::HeightFieldTileAtlas), and the attribute grids horizons are coloured by
 * another, one layer per coloured horizon. The quadtree (strata::MinMaxQuadtree: nodes, depth
 * intervals, horizon lists) and the colour table (one per horizon or 1024 over depth) are
 * float texture buffers; ints stored as floats are exact below 2^24, far above any tree built
 * here. The box spans the grid and the value range, slightly taller than the data so that
 * flat stacks still have back faces.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataHeightFieldStackBuffers_h
#define StrataHeightFieldStackBuffers_h

#include "StrataGLObject.h"        // For strata::GLObject
#include "StrataRenderingModule.h" // For export macro
#include "vtkNew.h"                // For vtkNew

#include <string> // For std::string
#include <vector> // For std::vector

namespace strata
{
class HeightFieldStack;
}
namespace strata
{
class MinMaxQuadtree;
}
class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT HeightFieldStackBuffers
{
public:
  HeightFieldStackBuffers();
  ~HeightFieldStackBuffers();
  HeightFieldStackBuffers(const HeightFieldStackBuffers&) = delete;
  HeightFieldStackBuffers& operator=(const HeightFieldStackBuffers&) = delete;

  /// The in-core heights; false with `error` set beyond the GPU's limits or memory.
  bool UploadHeights(vtkOpenGLRenderWindow* window,
    const strata::HeightFieldStack& stack,
    std::string& error);
  bool HasHeights() const { return static_cast<bool>(this->Heights); }
  unsigned int GetHeightTexture() const { return this->Heights.GetName(); }
  /**
   * Attribute grids on the same lateral grid (one layer each, NaN for no data), for horizons
   * coloured by a second grid; an empty stack releases them.
   */
  bool UploadAttributes(vtkOpenGLRenderWindow* window,
    const strata::HeightFieldStack& attributes,
    std::string& error);
  unsigned int GetAttributeTexture() const { return this->Attributes.GetName(); }

  void UploadTree(vtkOpenGLRenderWindow* window, const strata::MinMaxQuadtree& tree);
  /// The proxy box over an nx x ny grid and the value range (empty range: 0).
  void UploadBox(int nx, int ny, const double valueRange[2]);
  /// RGBA per entry.
  void UploadColors(vtkOpenGLRenderWindow* window, const std::vector<float>& colors);

  /// Binds the box's vertex array, its attribute set up for `program` (vertexGrid).
  void BindBox(vtkShaderProgram* program);
  /// Draws the box's 12 triangles (the vertex array bound) and unbinds it.
  void DrawBox();

  /// The tree's buffers (and the colours when `colors`) on texture units, their uniforms set.
  void Activate(vtkShaderProgram* program, bool colors);
  void Deactivate(bool colors);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  strata::GLObject Heights{ strata::GLObject::Kinds::Texture };
  strata::GLObject Attributes{ strata::GLObject::Kinds::Texture };
  vtkNew<vtkOpenGLBufferObject> NodeBuffer, IntervalBuffer, LayerListBuffer, ColorBuffer;
  vtkNew<vtkTextureObject> NodeTexture, IntervalTexture, LayerListTexture, ColorTexture;
  vtkNew<vtkOpenGLBufferObject> BoxVertices, BoxIndices;
  strata::GLObject BoxArray{ strata::GLObject::Kinds::VertexArray };
  vtkShaderProgram* ArrayProgram = nullptr; ///< the program the attribute was set up for
};
}

#endif
