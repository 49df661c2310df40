// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkSegyVolumeReader
 * @brief   Streams a post-stack SEG-Y volume as vtkImageData, inline by inline, through segyio.
 *
 * Seismic volumes are the largest inputs Strata converts to brick pools, and SEG-Y files are
 * rarely as tidy as the standard says: the inline and crossline numbers sit at other byte
 * positions than revision 1's 189 and 193, traces come in any order, some grid positions have
 * no trace. This reader finds the inline/crossline grid from the trace headers alone and then
 * reads only the traces of the inlines a request asks for, so vtkImageToPagePoolWriter's
 * slab-by-slab conversion never holds more than a slab of the volume. (VTK's own vtkSegYReader
 * reads the whole file into memory and takes the line numbers from fixed positions.)
 *
 * RequestInformation opens the file with segyio (segyio/segy.h), reads the binary header (sample
 * count, sample interval, format code) and every trace header (inline and crossline numbers),
 * and builds the (inline, crossline) -> trace index. As in segyio, the binary header's sample
 * count is trusted (the first trace header's where it is 0) and trace headers' counts are not:
 * real files leave them stale. Traces of another length show as a file size that is not a
 * whole number of traces. The grid spans the distinct
 * inline numbers from the first to the last with a step equal to the greatest common divisor of
 * their differences (inlines 100, 102, 106 give step 2 and 4 inlines), and likewise for the
 * crosslines. RequestData reads, for each inline of the update extent, the traces of the
 * requested crosslines and only the requested samples (CAN_PRODUCE_SUB_EXTENT).
 *
 * Axes. Index x is the crossline, y the sample (time or depth), z the inline: z is the axis
 * vtkImageToPagePoolWriter streams along, so a slab is a set of whole inlines, and one inline
 * (nx crosslines by ny samples) is the unit read.
 *
 * Placement (World, and Automatic when the trace headers carry coordinates). The output's
 * origin, spacing and direction matrix are the survey's place in the coordinates of its trace
 * headers (CDP X and Y at bytes 181 and 185 by default, or source X/Y at 73 and 77, ...), each
 * multiplied by the coordinate scalar at byte 71 (negative: divided by its magnitude; 0: 1).
 * Map X and Y are an affine function of the (inline, crossline) grid indices, fitted by least
 * squares to every trace: any rotation, either handedness, bins of any size (a shear too, with
 * a warning). Index x runs along the fitted crossline direction with spacing the distance
 * between neighbouring grid crosslines, index z along the inline direction likewise, and index
 * y straight down: world z = VerticalScale x (delay recording time + sample x interval), in ms
 * for time data (the header's interval in microseconds / 1000; for depth data the header's unit
 * / 1000), with VerticalScale -1 by default, the convention of vtkStackedHeightFieldMapper's
 * HeightScale (-1: depths and times grow downwards). So horizons exported in the survey's map
 * projection (e.g. Irap grids of two-way time in ms, drawn with HeightScale -1) and the volume
 * line up with no transform. Strata's mappers honour the direction matrix (so do page pools:
 * strata-convert keeps the placement); the same index -> world matrix is GetGridToWorld() and
 * the output's field data array "GridToWorld" (16 values, row-major), for consumers that ignore
 * direction matrices (set it as a prop's UserMatrix of an image with unit spacing, zero origin
 * and identity direction). Traces off the fitted lattice by more than MaximumFitResidual bins,
 * coordinates that do not change along both axes (wrong byte positions), geographic coordinates
 * (trace header byte 89 = 2, 3, 4), and a single inline or crossline (a 2-D line: one axis
 * cannot be placed) are errors under World; Automatic falls back to LineNumbers with a warning
 * for the last two and with no message when every X and Y is zero (no georeference at all).
 *
 * Placement LineNumbers (the frame of earlier versions): the direction matrix maps index
 * (x, y, z) to world (y, z, x), a proper rotation, so the world frame is the one of
 * vtkHorizonColumnReader's index coordinates: world x = inline number, world y = crossline
 * number, world z = time in ms growing upwards (+z). Origin: first inline, first crossline, and
 * the delay recording time; spacing: crossline step, sample interval, inline step.
 *
 * Every trace must have the delay recording time (trace header bytes 109-110, ms) of the first
 * trace (an error otherwise: the samples would not line up in depth). Grid positions without a
 * trace read as NaN, with a warning that says how many.
 *
 * Samples. Format codes 1 (IBM float), 2 (32-bit integer), 3 (16-bit integer), 5 (IEEE float)
 * and 8 (8-bit integer) are read, big-endian as the standard requires, and always output as
 * float ("amplitude" by default): exact for every 8- and 16-bit integer and every IEEE float;
 * IBM floats are converted by segyio (exact apart from the rare values beyond IEEE single's
 * range or precision); 32-bit integers beyond 2^24 in magnitude are rounded. One output type
 * keeps missing traces representable: grid positions without a trace read as NaN, which
 * strata::PagePoolWriter leaves out of page and global min/max. SampleFormat overrides a wrong code
 * in the binary header.
 *
 * Byte positions (1-based, as in the standard): a position where SEG-Y revision 1 defines a
 * field is read with that field's width (2 or 4 bytes, as segyio does); any other position in
 * [1, 237] is read as a 4-byte big-endian integer.
 *
 * Errors, reported with vtkErrorMacro and leaving an empty output: those of the placement above,
 * traces of different delay recording times, missing or unreadable file, a
 * file shorter than its headers or not a whole number of traces (truncated, or traces of another
 * length), an unsupported format code, a byte position out of range, two traces at one
 * (inline, crossline) position (pre-stack gathers, or wrong byte positions), a grid too sparse
 * for its traces (wrong byte positions) or too large, and a file that changed or fails to read
 * between the information and the data pass. Little-endian (byte-swapped) files are not
 * supported.
 *
 * @sa vtkImageToPagePoolWriter vtkHorizonColumnReader
 */
#ifndef vtkSegyVolumeReader_h
#define vtkSegyVolumeReader_h

#include "StrataIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <memory> // For std::unique_ptr

class vtkMatrix4x4;

class STRATAIO_EXPORT vtkSegyVolumeReader : public vtkImageAlgorithm
{
public:
  static vtkSegyVolumeReader* New();
  vtkTypeMacro(vtkSegyVolumeReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The SEG-Y file to read. Default: none.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// 1-based trace-header byte position of the inline number. Default 189 (SEG-Y rev 1).
  vtkSetMacro(InlineByte, int);
  vtkGetMacro(InlineByte, int);
  ///@}

  ///@{
  /// 1-based trace-header byte position of the crossline number. Default 193 (SEG-Y rev 1).
  vtkSetMacro(CrosslineByte, int);
  vtkGetMacro(CrosslineByte, int);
  ///@}

  ///@{
  /// 1-based trace-header byte positions of the map X and Y coordinates and of their scalar.
  /// Defaults 181, 185 (CDP X, Y, SEG-Y rev 1) and 71; source X, Y are at 73 and 77.
  vtkSetMacro(XByte, int);
  vtkGetMacro(XByte, int);
  vtkSetMacro(YByte, int);
  vtkGetMacro(YByte, int);
  vtkSetMacro(CoordinateScalarByte, int);
  vtkGetMacro(CoordinateScalarByte, int);
  ///@}

  enum class Placements
  {
    Automatic,   ///< World if any trace has a non-zero X or Y, else LineNumbers
    World,       ///< trace coordinates, z = VerticalScale x time or depth; needs coordinates
    LineNumbers, ///< world (inline number, crossline number, +time): earlier versions' frame
  };

  ///@{
  /// Where the output is placed (see the class comment). Default Automatic.
  void SetPlacement(Placements placement);
  Placements GetPlacement() const { return this->Placement; }
  ///@}

  ///@{
  /// World z of a sample = VerticalScale x its time (ms) or depth, under World placement; not 0.
  /// Default -1 (downwards, as vtkStackedHeightFieldMapper's HeightScale -1).
  vtkSetMacro(VerticalScale, double);
  vtkGetMacro(VerticalScale, double);
  ///@}

  ///@{
  /// Largest distance of a trace from its place on the fitted lattice, in bins (of the smaller
  /// bin side), beyond which World placement is an error. Default 0.25: coordinates rounded to
  /// 1 m on 6.25 m bins are off by up to 0.11 bins; a trace a bin off its place is refused.
  vtkSetClampMacro(MaximumFitResidual, double, 0.0, 1e30);
  vtkGetMacro(MaximumFitResidual, double);
  ///@}

  ///@{
  /// Sample format code to use instead of the binary header's (1, 2, 3, 5 or 8); 0 trusts the
  /// header. Default 0.
  vtkSetMacro(SampleFormat, int);
  vtkGetMacro(SampleFormat, int);
  ///@}

  ///@{
  /// Name of the output point-data array. Default: "amplitude".
  vtkSetStringMacro(ArrayName);
  vtkGetStringMacro(ArrayName);
  ///@}

  ///@{
  /// What the last RequestInformation found (0 before, or after a failure): traces in the file,
  /// grid positions without a trace, the format code used, the first inline and crossline
  /// numbers and the steps between them.
  vtkGetMacro(NumberOfTraces, vtkIdType);
  vtkGetMacro(NumberOfMissingTraces, vtkIdType);
  vtkGetMacro(FormatCode, int);
  vtkGetMacro(FirstInline, int);
  vtkGetMacro(InlineStep, int);
  vtkGetMacro(FirstCrossline, int);
  vtkGetMacro(CrosslineStep, int);
  ///@}

  ///@{
  /// The placement the last RequestInformation found: whether it is World (trace coordinates);
  /// the largest distance of a trace from its fitted place (world units, 0 for LineNumbers);
  /// the angle, degrees counterclockwise from world +x, of the direction of index x (increasing
  /// crossline numbers); the index -> world matrix (origin, spacing and direction together;
  /// identity before a successful RequestInformation).
  vtkGetMacro(Georeferenced, bool);
  vtkGetMacro(FitResidual, double);
  vtkGetMacro(GridRotation, double);
  vtkMatrix4x4* GetGridToWorld();
  ///@}

  /// Traces read by the last RequestData (missing ones not counted), to check that a sub-extent
  /// reads only its own inlines.
  vtkGetMacro(NumberOfTracesRead, vtkIdType);

protected:
  vtkSegyVolumeReader();
  ~vtkSegyVolumeReader() override;

  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;
  char* ArrayName = nullptr;
  int InlineByte = 189;
  int CrosslineByte = 193;
  int SampleFormat = 0;
  int XByte = 181;
  int YByte = 185;
  int CoordinateScalarByte = 71;
  Placements Placement = Placements::Automatic;
  double VerticalScale = -1.0;
  double MaximumFitResidual = 0.25;
  bool Georeferenced = false;
  double FitResidual = 0.0;
  double GridRotation = 0.0;
  vtkIdType NumberOfTraces = 0;
  vtkIdType NumberOfMissingTraces = 0;
  int FormatCode = 0;
  int FirstInline = 0;
  int InlineStep = 0;
  int FirstCrossline = 0;
  int CrosslineStep = 0;
  vtkIdType NumberOfTracesRead = 0;

private:
  vtkSegyVolumeReader(const vtkSegyVolumeReader&) = delete;
  void operator=(const vtkSegyVolumeReader&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
