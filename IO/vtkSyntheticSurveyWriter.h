// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkSyntheticSurveyWriter
 * @brief   Writes a synthetic post-stack SEG-Y survey from a horizon stack: reflectivity at the
 *          horizons' interfaces convolved with a Ricker wavelet, plus seeded noise.
 *
 * For demos and tests of the subsurface scene: a seismic volume whose reflections lie exactly
 * where the horizons are, in the same map coordinates, so that the volume read back by
 * vtkSegyVolumeReader (world placement) and the horizons drawn by vtkStackedHeightFieldMapper
 * with HeightScale -1 must line up.
 *
 * Inputs: horizons as vtkImageData of nx x ny x 1 points on port 0 (repeatable, top to
 * bottom), each on its own lateral grid (origin, spacing, and a direction matrix whose first
 * two columns are horizontal: any grid rotation), the active scalar (or first point array) the
 * horizon's two-way time in ms, or its depth, growing downwards: the values drawn with
 * HeightScale -1. NaN and |v| >= 1e30 are holes. The survey: Inlines x Crosslines traces, grid
 * index (0, 0) at map (OriginX, OriginY); crossline index x moves CrosslineBin along the azimuth
 * Rotation (degrees counterclockwise from +x), inline index i moves InlineBin 90 degrees
 * counterclockwise from there (the layout vtkSegyVolumeReader reports as GridRotation); line
 * numbers FirstInline + i and FirstCrossline + x.
 *
 * Each trace samples every horizon at its map position (bilinear; a hole, or a position off the
 * horizon's grid, leaves that horizon out of the trace). Layer k lies below horizon k - 1 and
 * above horizon k, with acoustic impedance Impedance(k) (N + 1 layers for N horizons). Going
 * down a trace through the horizons present there, ordered by time, the reflection coefficient
 * at horizon h is (Z(h + 1) - Z(above)) / (Z(h + 1) + Z(above)), where Z(above) is the layer
 * below the previous horizon crossed (layer 0 above the first): a missing horizon merges its
 * two layers, crossing horizons are taken in the order they are met. The trace is the sum of
 * the reflection coefficients times a Ricker wavelet (1 - 2 (pi f t)^2) exp(-(pi f t)^2) of peak
 * frequency PeakFrequency (Hz for times in ms; cycles per 1000 units for depths), evaluated at
 * each sample time exactly (no spike put on the nearest sample: a horizon between two samples
 * stays there), plus Gaussian noise of standard deviation NoiseLevel (in reflection coefficient
 * units), from a generator seeded by Seed and the trace's grid position (the same file for the
 * same settings, whatever the machine).
 *
 * The file: SEG-Y rev 1, big-endian, IEEE float samples (format 5), inline/crossline numbers at
 * bytes 189/193 (and 9/21), CDP X/Y at 181/185 and source X/Y at 73/77 times the
 * CoordinateScalar at 71 (-100 by default: centimetres), coordinate units 1 (length), delay
 * recording time StartTime (ms, bytes 109-110), Samples samples SampleInterval ms apart
 * (binary header and every trace, in microseconds). Written to <FileName>.tmp-<pid> and renamed
 * when complete; progress events per inline. Errors (vtkErrorMacro, Write() returns false,
 * nothing left under FileName): no horizons, a horizon not one point thick or without scalars,
 * a wrong number of impedances or a non-positive one, a geometry out of SEG-Y's ranges (sample
 * interval not a whole number of microseconds up to 65535, StartTime outside [0, 32767],
 * coordinates beyond 32-bit integers at the scalar), and a file that cannot be written.
 *
 * @code
 * vtkNew<vtkSyntheticSurveyWriter> survey;
 * survey->AddInputConnection(top->GetOutputPort());
 * survey->AddInputConnection(base->GetOutputPort());
 * survey->SetOrigin(456000, 6780000);
 * survey->SetRotation(30);
 * survey->SetLines(100, 120);    // inlines, crosslines
 * survey->SetBins(25.0, 12.5);   // inline, crossline bin (m)
 * survey->SetSamples(500, 2.0, 0); // count, interval (ms), start (ms)
 * survey->SetFileName("synthetic.sgy");
 * survey->Write();
 * @endcode
 *
 * @sa vtkSegyVolumeReader vtkStackedHeightFieldMapper
 */
#ifndef vtkSyntheticSurveyWriter_h
#define vtkSyntheticSurveyWriter_h

#include "StrataIOModule.h" // For export macro
#include "vtkAlgorithm.h"

#include <string> // For std::string
#include <vector> // For std::vector

class STRATAIO_EXPORT vtkSyntheticSurveyWriter : public vtkAlgorithm
{
public:
  static vtkSyntheticSurveyWriter* New();
  vtkTypeMacro(vtkSyntheticSurveyWriter, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The SEG-Y file to write. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// Map position of grid index (0, 0). Default (456000, 6780000).
  vtkSetVector2Macro(Origin, double);
  vtkGetVector2Macro(Origin, double);
  ///@}

  ///@{
  /// Azimuth of the crossline direction (increasing crossline numbers along an inline), degrees
  /// counterclockwise from +x. Default 30.
  vtkSetMacro(Rotation, double);
  vtkGetMacro(Rotation, double);
  ///@}

  ///@{
  /// Number of inlines and crosslines. Default 40 x 60.
  vtkSetVector2Macro(Lines, int);
  vtkGetVector2Macro(Lines, int);
  ///@}

  ///@{
  /// Inline and crossline bin sizes (distance between neighbouring inlines, crosslines).
  /// Default 25 x 12.5.
  vtkSetVector2Macro(Bins, double);
  vtkGetVector2Macro(Bins, double);
  ///@}

  ///@{
  /// Line number of the first inline and crossline. Default 1000 and 2000.
  vtkSetMacro(FirstInline, int);
  vtkGetMacro(FirstInline, int);
  vtkSetMacro(FirstCrossline, int);
  vtkGetMacro(FirstCrossline, int);
  ///@}

  ///@{
  /// Samples per trace, the interval between them (ms) and the time of the first (ms, whole).
  /// Default 500, 2 ms, 0.
  void SetSamples(int count, double interval, int start);
  vtkGetMacro(Samples, int);
  vtkGetMacro(SampleInterval, double);
  vtkGetMacro(StartTime, int);
  ///@}

  ///@{
  /// Acoustic impedance of layer `layer` (0: above the first horizon). Layers never set get
  /// 4e6 + 1e6 layer (impedance growing with depth: positive reflections).
  void SetImpedance(int layer, double impedance);
  double GetImpedance(int layer) const;
  ///@}

  ///@{
  /// Peak frequency of the Ricker wavelet, Hz. Default 25.
  vtkSetClampMacro(PeakFrequency, double, 1e-3, 1e6);
  vtkGetMacro(PeakFrequency, double);
  ///@}

  ///@{
  /// Standard deviation of the additive Gaussian noise, in reflection coefficient units, and
  /// the seed of its generator. Default 0.002 and 1.
  vtkSetClampMacro(NoiseLevel, double, 0.0, 1e30);
  vtkGetMacro(NoiseLevel, double);
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /// The coordinate scalar written at byte 71 (negative: coordinates are stored times its
  /// magnitude). Default -100.
  vtkSetMacro(CoordinateScalar, int);
  vtkGetMacro(CoordinateScalar, int);
  ///@}

  /// Writes the survey. Returns true on success.
  bool Write();

  /// The exact map position of grid index (inline i, crossline x) (before rounding to the
  /// coordinate scalar).
  void MapPosition(double i, double x, double position[2]) const;

  /// The wavelet's value at time `t` (ms) from its peak, for PeakFrequency.
  double Ricker(double t) const;

protected:
  vtkSyntheticSurveyWriter();
  ~vtkSyntheticSurveyWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;
  double Origin[2] = { 456000.0, 6780000.0 };
  double Rotation = 30.0;
  int Lines[2] = { 40, 60 };
  double Bins[2] = { 25.0, 12.5 };
  int FirstInline = 1000;
  int FirstCrossline = 2000;
  int Samples = 500;
  double SampleInterval = 2.0;
  int StartTime = 0;
  std::vector<double> Impedances;
  double PeakFrequency = 25.0;
  double NoiseLevel = 0.002;
  unsigned int Seed = 1;
  int CoordinateScalar = -100;

private:
  /// What keeps the settings from a valid SEG-Y survey of `horizons` horizons (empty: none).
  std::string CheckSettings(int horizons) const;
  /// Map coordinate -> stored integer: |CoordinateScalar| for a negative scalar, else 1 / it.
  double CoordinateFactor() const;

  vtkSyntheticSurveyWriter(const vtkSyntheticSurveyWriter&) = delete;
  void operator=(const vtkSyntheticSurveyWriter&) = delete;
};

#endif
