// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::TransferFunctionTable
 * @brief   A volume property's transfer functions as the ray casters sample them: tabulated,
 *          turned into extinction, uploaded, and rebuilt only when the property changes.
 *
 * One place for what the multi-volume ray caster (per input), the hybrid mapper's points and
 * the references all need: TableSize entries evenly over the union of the colour and opacity
 * functions' ranges, RGB colour and opacity per unit distance as VTK's GetTable computes them
 * (Tabulate), the opacity turned into extinction per unit length (TabulateExtinction), and a
 * 1-D RGBA32F texture of the latter, linear and clamped, read at texture coordinate
 * (s - TableRange[0]) * TableRange[1] + TableRange[2] for scalar s (entry i at its texel
 * centre). References integrate exactly the table the GPU samples by calling Tabulate.
 *
 * @sa vtkMultiVolumeRayCastMapper vtkHybridVolumeMapper strata::PreIntegrationTable
 */
#ifndef StrataTransferFunctionTable_h
#define StrataTransferFunctionTable_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkSmartPointer.h"       // For vtkSmartPointer
#include "vtkType.h"               // For vtkMTimeType

#include <vector> // For std::vector

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT TransferFunctionTable
{
public:
  /// Entries of the tables the mappers build.
  static constexpr int TableSize = 1024;

  /**
   * `size` entries of `property`'s functions of `component` evenly over `range` (the union
   * of the colour and opacity functions' ranges, widened to one unit when empty): RGB colour
   * (grey repeated for a grey function) and opacity per unit distance.
   */
  static void Tabulate(vtkVolumeProperty* property,
    int size,
    double range[2],
    std::vector<float>& rgb,
    std::vector<float>& opacity,
    int component = 0);

  /**
   * Tabulate's table with the opacity turned into extinction per unit length,
   * -ln(1 - a) / ScalarOpacityUnitDistance of the component (a capped at 1 - 1e-6 so that it
   * stays finite: a unit length then lets 1e-6 through), interleaved RGBA per entry; `opacity`
   * gets the tabulated opacity.
   */
  static void TabulateExtinction(vtkVolumeProperty* property,
    int size,
    double range[2],
    std::vector<float>& rgbTau,
    std::vector<float>& opacity,
    int component = 0);

  /**
   * The gradient opacity function of `property` (component 0), `size` entries evenly over its
   * range (widened to one unit when empty; clamped outside, as the texture is read). False, and
   * nothing filled, when the property has none (HasGradientOpacity) or it is disabled.
   */
  static bool TabulateGradientOpacity(vtkVolumeProperty* property,
    int size,
    double range[2],
    std::vector<float>& opacity);

  /// When `property`'s transfer functions last changed (those of its colour kind only: VTK's
  /// getters of the other kind would create, and switch to, a default).
  static vtkMTimeType GetMTime(vtkVolumeProperty* property, int component = 0);

  /// The opacity unit distance as the tables and the shaders divide by it: at least 1e-30 (VTK
  /// allows 0, and 0 / 0 is NaN on the GPU).
  static double GetUnitDistance(vtkVolumeProperty* property, int component = 0);

  TransferFunctionTable();
  ~TransferFunctionTable();
  TransferFunctionTable(const TransferFunctionTable&) = delete;
  TransferFunctionTable& operator=(const TransferFunctionTable&) = delete;

  /**
   * Tabulates `property`'s functions of `component` (TableSize entries, TabulateExtinction)
   * and uploads the texture when the property or component is another one or changed since the
   * last call. Returns whether it did.
   */
  bool Update(vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property, int component = 0);

  /// The RGBA32F texture (null before the first Update).
  vtkTextureObject* GetTexture() const;
  /// Scalar s to texture coordinate: (s - r[0]) * r[1] + r[2].
  const double* GetTableRange() const { return this->TableRange; }
  /// The scalar range the entries span.
  const double* GetScalarRange() const { return this->ScalarRange; }
  /// The uploaded table, RGB and extinction per entry.
  const std::vector<float>& GetRGBTau() const { return this->RGBTau; }
  /// The tabulated opacity per entry.
  const std::vector<float>& GetOpacity() const { return this->Opacity; }
  /// Increases with every rebuild (what depends on the table compares it).
  unsigned long GetBuildCount() const { return this->BuildCount; }

  /// Frees the texture (the owner calls it with the context current).
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkSmartPointer<vtkTextureObject> Texture;
  vtkVolumeProperty* Property = nullptr;
  int Component = 0;
  vtkMTimeType Time = 0;
  unsigned long BuildCount = 0;
  double TableRange[3] = { 0.0, 1.0, 0.0 };
  double ScalarRange[2] = { 0.0, 1.0 };
  std::vector<float> RGBTau;
  std::vector<float> Opacity;
};
}

#endif
