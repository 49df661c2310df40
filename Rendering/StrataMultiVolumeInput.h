// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::MultiVolumeInput
 * @brief   The GPU state of one input of vtkMultiVolumeRayCastMapper: its scalars (a brick
 *          tree for the atlas, or one plain texture), its transfer and pre-integration tables
 *          and its empty-space skip grid, each rebuilt only when what it depends on changed.
 *
 * Scalars are kept as float (exact for every input type) while the input image stays the
 * same; an in-core volume's brick tree (strata::VolumeBrickTree) is built from them for the atlas
 * (from a copy in their own type for native 8- and 16-bit storage, strata::BrickAtlasFormat), a
 * paged one's comes from strata::VolumePager. The transfer table (strata::TransferFunctionTable) is
 * rebuilt when the volume property changes; the pre-integration table (strata::PreIntegrationTable)
 * follows it and the sample distance; the skip grid's cell ranges follow the data (or, paged,
 * the level-0 bricks' ranges from the page table) and its distances the transfer table.
 * Scalars of several components (vtkVolumeProperty's IndependentComponents) are kept as one
 * texture with a channel each, with a transfer table per independent component; when the frame
 * uses the atlas (a paged volume is in it) each component has its own brick tree instead and
 * is a volume of one scalar there (ComponentVisibility, GetComponentEmptyScalar).
 * Bind() sets the volume's uniforms for volume n of a fragment's program.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataMultiVolumeInput_h
#define StrataMultiVolumeInput_h

#include "StrataBrickAtlasFormat.h"          // For strata::BrickAtlasFormat::Storage
#include "StrataGLObject.h"                  // For strata::GLObject
#include "StrataMultiVolumeShaderComposer.h" // For Components
#include "StrataPreIntegrationTable.h"       // For strata::PreIntegrationTable
#include "StrataRenderingModule.h"           // For export macro
#include "StrataTransferFunctionTable.h"     // For strata::TransferFunctionTable
#include "StrataVolumeBrickTree.h"           // For strata::VolumeBrickTree::ScalarType
#include "StrataVolumeSkipGrid.h"            // For strata::VolumeSkipGrid
#include "vtkMultiVolumeRayCastMapper.h"     // For Classifications
#include "vtkSmartPointer.h"                 // For vtkSmartPointer

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT MultiVolumeInput
{
public:
  using Classifications = vtkMultiVolumeRayCastMapper::Classifications;
  using Components = strata::MultiVolumeShaderComposer::Components;

  /**
   * The components of `scalars` under `property`'s IndependentComponents, as vtkVolumeProperty
   * defines them: 1 to 4 independent, 2 or 4 dependent. False, with `error` saying what they
   * are, for others.
   */
  static bool GetComponentMode(vtkDataArray* scalars,
    vtkVolumeProperty* property,
    Components& mode,
    std::string& error);
  /**
   * Whether a volume of several components is drawn as asked: they make a composite medium,
   * post-classified, without shading or gradient opacity.
   */
  static bool DrawsComponentsAsAsked(vtkVolumeProperty* property,
    int blendMode,
    Classifications classification);
  /**
   * The components of port `port`'s `image` (the array `mapper`'s GetScalars picks):
   * GetComponentMode, false with an error of `mapper` for what the property does not define; a
   * volume of several components is composite (`blendMode` set), and what it cannot draw as
   * asked is warned of once (`warned`).
   */
  static bool CollectComponents(vtkMultiVolumeRayCastMapper* mapper,
    int port,
    vtkImageData* image,
    vtkVolumeProperty* property,
    int& blendMode,
    Components& mode,
    bool& warned);

  MultiVolumeInput();
  ~MultiVolumeInput();
  MultiVolumeInput(const MultiVolumeInput&) = delete;
  MultiVolumeInput& operator=(const MultiVolumeInput&) = delete;

  /**
   * Copies `scalars` (component 0, one per point of `image`) as float when `image` is another
   * one or changed since; the brick tree and plain texture then follow. Of several components
   * (at most 4) all are kept, interleaved, with their colour ranges. Returns whether it copied.
   */
  bool UpdateScalars(vtkImageData* image, vtkDataArray* scalars, vtkWindow* window);
  /// The components UpdateScalars kept (1 for one scalar).
  int GetNumberOfComponents() const { return this->NumberOfComponents; }
  /**
   * The scalars of RGBA component `c` (0, 1, 2) that map to colour 0 and 1, as VTK 9.1 reads
   * them (its textures normalise 8- and 16-bit integers, keep float as it is, and scale wider
   * types over each component's range): [0, 255] for unsigned char, [0, 127] signed char,
   * [0, 65535] unsigned short, [0, 32767] short, [0, 1] float, else the finite range.
   */
  static void GetColorRange(vtkDataArray* scalars, int c, double range[2]);
  /// RGBA: the colour ranges of `scalars`' type (GetColorRange), for a paged volume (whose
  /// scalars are not kept: `scalars` are its reader's coarse level, of the pool's type).
  void UpdateColorRanges(vtkDataArray* scalars);

  /**
   * The transfer tables of components 1, 2, ... of independent components (component 0's is
   * UpdateTransfer's), each from the property's functions and unit distance of that component.
   */
  void UpdateComponentTables(vtkOpenGLRenderWindow* window,
    vtkVolumeProperty* property,
    Components mode);
  /// Whether the scalars are kept for `image` as it is now.
  bool HasScalarsOf(vtkImageData* image) const;

  /**
   * The in-core brick tree for bricks of `brickSize`, built when missing or of another size or
   * type: `native`, in the scalars' own type when 8- or 16-bit (GetScalarType(); its coarse
   * levels rounded as page pools round them), else float. Returns -1 with `error` set when it
   * cannot be built, 1 when it was (re)built, 0 otherwise.
   */
  int UpdateTree(const int dims[3], int brickSize, bool native, std::string& error);
  /**
   * The in-core tree of `component`, null if none (paged volumes use strata::VolumePager's). A
   * volume of several components has one tree per component (UpdateTree builds them all): each is a
   * volume of one scalar in the atlas, as a paged set of components is.
   */
  const strata::VolumeBrickTree* GetTree(int component = 0) const
  {
    return component == 0                         ? this->Tree.get()
           : component < this->NumberOfComponents ? this->ComponentTrees[component - 1].Tree.get()
                                                  : nullptr;
  }

  /// The whole volume as one 3-D texture (no atlas): R8 or R16 for 8- and 16-bit scalars as
  /// `storage` says (strata::BrickAtlasFormat::Choose), else R32F or a float channel per component;
  /// made once per scalars and storage.
  void UpdatePlainTexture(vtkOpenGLRenderWindow* window,
    const int dims[3],
    strata::BrickAtlasFormat::Storage storage);
  /// The type the one-component scalars are stored as natively (strata::BrickAtlasFormat).
  strata::VolumeBrickTree::ScalarType GetScalarType() const { return this->ScalarType; }
  /// The plain texture's texel type (Float32 until UpdatePlainTexture).
  strata::VolumeBrickTree::ScalarType GetPlainTextureType() const { return this->DataType; }

  /// The transfer table and what follows from it (pre-integration input, empty scalar).
  void UpdateTransfer(vtkOpenGLRenderWindow* window, vtkVolumeProperty* property);
  /**
   * The gradient opacity table (256 entries,
   * strata::TransferFunctionTable::TabulateGradientOpacity) and its texture, rebuilt when the
   * function changes; none when the property has none.
   */
  void UpdateGradientOpacity(vtkOpenGLRenderWindow* window, vtkVolumeProperty* property);
  bool HasGradientOpacity() const { return this->GradientTexture != nullptr; }

  /// The largest opacity the interpolated table reaches for scalars in [lo, hi].
  double MaxOpacity(double lo, double hi) const;

  /**
   * The volume's blend mode (vtkVolumeMapper::BlendModes) and, for ISOSURFACE, its isovalues:
   * they decide which data may be left out. Composite and additive: data of zero opacity; MIP
   * (MinIP): data whose opacity is zero down to (up to) the table's end, read as that end, so
   * that a left-out brick can neither raise the maximum nor lower the minimum into visible
   * values; average: nothing (every sample counts); isosurface: skip cells whose range holds no
   * visible isovalue, and no brick (a stand-in next to data would make false contours).
   */
  void SetBlendMode(int mode, const std::vector<double>& isoValues);
  int GetBlendMode() const { return this->BlendMode; }
  /// What a brick of scalars in [lo, hi] may show under the blend mode (0: leave it out).
  double BrickVisibility(double lo, double hi) const;
  /// The same for a skip-grid cell (only samples are skipped there, none replaced).
  double CellVisibility(double lo, double hi) const;
  /// The scalar left-out bricks read under the blend mode (see SetBlendMode).
  double GetEmptyScalar() const;
  /**
   * Of component `c` of a volume in the atlas: what a brick of its values in [lo, hi] may show,
   * and the value left-out bricks read. One component: BrickVisibility and GetEmptyScalar.
   * Several (composite): independent, its own table's opacity, and nothing for a component of
   * weight 0 (vtkVolumeProperty::GetComponentWeight: it shows nothing, so none of its bricks is
   * paged); dependent, the opacity component's (the main table), and the colour components
   * always count (their bricks are kept wherever the volume is).
   */
  double ComponentVisibility(Components mode, int c, double lo, double hi) const;
  /// Whether component c shows anything: false for an independent component of weight 0 (as
  /// UpdateComponentTables last read the property).
  bool ShowsComponent(int c) const { return this->ComponentWeights[c] > 0.0; }
  double GetComponentEmptyScalar(Components mode, int c) const;

  /**
   * The skip grid: cell ranges from the scalars (`cellSize` voxels) or, for a paged volume,
   * from `poolTree`'s level-0 bricks (rebuilt when `pool` names another pool); distances
   * classified again when the transfer table changed; uploaded as R8UI. Of dependent
   * components, the ranges are those of the component the opacity reads (`opacityComponent`).
   */
  void UpdateSkipGrid(const strata::VolumeBrickTree* poolTree,
    const std::string& pool,
    const int dims[3],
    int cellSize,
    int opacityComponent = 0);
  /// The component the opacity of `mode` reads when it is one (dependent), else -1.
  static int GetOpacityComponent(Components mode);

  /// The pre-integration table of the classification at `sampleDistance`, uploaded on change.
  void UpdatePreIntegration(vtkOpenGLRenderWindow* window,
    Classifications classification,
    int tableSize,
    double sampleDistance);

  /// How volume n of a fragment is drawn this frame.
  struct Binding
  {
    Classifications Classification = Classifications::PostClassification;
    bool Atlas = true;
    unsigned int IndexTexture = 0;    ///< the atlas's index texture of this volume
    const int* TableBricks = nullptr; ///< level-0 bricks per axis (the index's size)
    int BrickSize = 0;                ///< of the atlas
    /// Texels normalised (atlas or plain texture): value = texel Decode[0] + Decode[1].
    bool Normalized = false;
    float Decode[2] = { 1.0f, 0.0f };
    bool Skipping = true;
    bool Shaded = false;
    double SampleDistance = 1.0;
    const float* LocalToIndex = nullptr; ///< column-major
    const int* Dims = nullptr;
    /// Not composite: the unit distance, isovalues (ISOSURFACE) or the normalisation and
    /// AverageRange (reductions) are set too; the transfer table is bound whatever the
    /// classification (contours and layers are coloured by it).
    int BlendMode = 0;
    const double* AverageRange = nullptr;
    const float* CropLo = nullptr; ///< cropped: the planes in index coordinates, and the flags
    const float* CropHi = nullptr;
    int CropFlags = 0;
    bool GradientOpacity = false; ///< composite: opacity times the gradient opacity function
    Components ComponentMode = Components::One; ///< several: read from the plain texture
    /// Several in the atlas: the index textures of components 1, 2, 3 (each its own volume).
    unsigned int ComponentIndexTextures[3] = { 0, 0, 0 };
  };
  /**
   * Sets volume n's uniforms on `program` and binds its textures: vtkTextureObjects on their
   * own units, raw textures on units of `window`'s manager appended to `rawUnits` (the caller
   * frees them after the draw, with Unbind()).
   */
  void Bind(vtkOpenGLRenderWindow* window,
    vtkShaderProgram* program,
    int n,
    vtkVolumeProperty* property,
    const Binding& binding,
    std::vector<int>& rawUnits);
  /// Deactivates the vtkTextureObjects Bind() activated.
  void Unbind(const Binding& binding);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  /// Whether `mode` is independent components (2, 3 or 4).
  static bool IsIndependent(Components mode);

  void BindBlendMode(vtkShaderProgram* program,
    const std::string& n,
    vtkVolumeProperty* property,
    const Binding& binding);
  void BindComponents(vtkShaderProgram* program,
    const std::string& n,
    vtkVolumeProperty* property,
    const Binding& binding);

  std::vector<float> Scalars;               ///< the input as float; a float brick tree borrows it
  std::vector<unsigned char> NativeScalars; ///< in their own type: a native tree borrows them
  int NumberOfComponents = 1;
  strata::VolumeBrickTree::ScalarType ScalarType = strata::VolumeBrickTree::ScalarType::Float32;
  strata::VolumeBrickTree::ScalarType DataType =
    strata::VolumeBrickTree::ScalarType::Float32; ///< Data's
  std::vector<float> ComponentScalars;            ///< several components: all, interleaved
  double ColorRanges[3][2] = { { 0, 1 }, { 0, 1 }, { 0, 1 } }; ///< RGBA: GetColorRange
  strata::TransferFunctionTable ComponentTables[3];            ///< independent components 1, 2, 3
  double ComponentWeights[4] = { 1.0, 1.0, 1.0, 1.0 };         ///< UpdateComponentTables's
  vtkImageData* DataInput = nullptr;
  vtkMTimeType DataTime = 0;
  std::unique_ptr<strata::VolumeBrickTree> Tree;
  /// Components 1, 2, 3 (several): their values (float; kept only while a float tree borrows
  /// them) or native copies, and trees.
  struct ComponentTree
  {
    std::vector<float> Values;
    std::vector<unsigned char> Native;
    std::unique_ptr<strata::VolumeBrickTree> Tree;
  };
  ComponentTree ComponentTrees[3];
  vtkSmartPointer<vtkTextureObject> Data; ///< plain texture (no atlas)
  strata::TransferFunctionTable Table;
  double EmptyScalar = 0.0;
  int BlendMode = 0;
  std::vector<double> IsoValues;                     ///< ascending
  vtkSmartPointer<vtkTextureObject> GradientTexture; ///< R32F gradient opacity table
  double GradientRange[2] = { 0.0, 1.0 };
  vtkMTimeType GradientTime = 0;
  strata::PreIntegrationTable PreIntegration;
  vtkSmartPointer<vtkTextureObject> PreTable;
  unsigned long PreTableCount = 0; ///< build count of the uploaded table
  int PreTableKind = -1;           ///< classification it was uploaded for
  strata::VolumeSkipGrid Skip;
  strata::GLObject SkipTexture{ strata::GLObject::Kinds::Texture }; ///< R8UI distances
  unsigned long SkipTime = 0;    ///< distances classified for this table build
  vtkMTimeType SkipDataTime = 0; ///< cell ranges built from this data (1: from a pool)
  int SkipComponent = 0;         ///< the component they were built from
  std::string SkipPool;          ///< the pool the paged ranges came from
};
}

#endif
