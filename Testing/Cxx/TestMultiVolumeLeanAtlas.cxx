// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The lean atlas (strata::BrickAtlasFormat): 8- and 16-bit volumes stored in R8 / R16 bricks, int16
// offset into R16, decoded in the shader. For uint8, uint16 and int16 copies of the blob volume
// (its transfer functions mapped alike), in core and paged:
// - the atlas's type and bytes per brick, and 4x / 2x the slots of float storage in one budget;
// - the native image equals float storage's (level 0 is exact, the decode only rounds), for the
//   atlas and for plain textures: native and float storage are two programs (the decode,
//   FragmentKey::Normalized), so within ImagePolicy::TwoProgramsMax, 1 of 255
//   (StrataImagePolicy.h rule 2; llvmpipe gives 0 for R16, 8-bit data in R16 too, and 1 for R8,
//   whose filtering is coarser; an H200 gives 1 for R16 as well);
// - the atlas equals the plain texture (two programs: within 1 of 255);
// - the image against the double-precision reference, with the Atlas case's bounds;
// - paged from a pool of the same type, converged: equal to the in-core image (paged vs in core,
//   two programs: max <= 1, 1 on an H200);
// - a uint8 and an int16 volume overlapping share an R16 atlas, equal to float storage (max 1);
// - the decode is compiled only where texels are normalised.
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkMultiVolumeRayCastMapper.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkTransform.h"
#include "vtkVolumeProperty.h"

#include <iostream>
#include <sstream>
#include <string>

namespace
{
using namespace strata_test;

using Storages = vtkMultiVolumeRayCastMapper::ScalarStorages;

struct TypedCase
{
  const char* Name;
  int VTKType;
  double Scale; ///< value = Scale blob + Offset, rounded
  double Offset;
  Storages Storage;
  const char* AtlasType;
  int TexelBytes;
  double MaxToFloat; ///< bound on the difference to float storage, of 255
};

// Native against float storage is two programs (the decode): ImagePolicy::TwoProgramsMax. R8 is
// also filtered at lower precision, 1 of 255 on llvmpipe already (the same bound, kept as its own
// number: it is not the compiler's); R16, 8-bit values times 257, exactly on llvmpipe, 1 on an
// H200.
using ImagePolicy::TwoProgramsMax;
const TypedCase Cases[] = {
  { "uint8", VTK_UNSIGNED_CHAR, 1.0, 0.0, Storages::Native, "uint8", 1, 1.0 },
  { "uint8-r16", VTK_UNSIGNED_CHAR, 1.0, 0.0, Storages::Normalized16, "uint16", 2, TwoProgramsMax },
  { "uint16", VTK_UNSIGNED_SHORT, 250.0, 0.0, Storages::Native, "uint16", 2, TwoProgramsMax },
  { "int16", VTK_SHORT, 250.0, -28000.0, Storages::Normalized16, "uint16", 2, TwoProgramsMax },
};

/// A bound of 255 as the messages print it ("1", not "1.000000").
std::string Of255(double bound)
{
  std::ostringstream text;
  text << bound;
  return text.str();
}

/// The blob (values 0 .. 230) as `vtkType`, with its property mapped alike.
vtkSmartPointer<vtkImageData> Typed(vtkImageData* blob, int vtkType, double scale, double offset)
{
  return CopyAsType(blob, vtkType, scale, offset);
}

vtkSmartPointer<vtkVolumeProperty> TypedProperty(int variant, double scale, double offset)
{
  auto p = MakeVolumeProperty(variant);
  MapTransferFunctions(p, scale, offset);
  return p;
}

int MaxDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  return static_cast<int>(ImageError(a, b).Max);
}

void TypedVolume(const TypedCase& c, const TestPaths& paths, bool& ok)
{
  const std::string tag = std::string("LeanAtlas-") + c.Name;
  VolumeScene s(paths.Output);
  auto blob = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  auto image = Typed(blob, c.VTKType, c.Scale, c.Offset);
  s.Add(image, TypedProperty(0, c.Scale, c.Offset));
  s.UseMultiVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  s.Mapper->SetBrickSize(16);

  // Float storage, then native: the same image, 1/4 or 1/2 of the bytes per brick.
  s.Mapper->SetScalarStorage(Storages::Float32);
  s.Win->Render();
  const auto floats = ReadRGB(s.Win);
  Check(s.Mapper->GetAtlasBytesPerBrick() == 16 * 16 * 16 * 4,
    tag + ": float storage takes 16 KiB a brick");
  s.Mapper->SetScalarStorage(c.Storage);
  s.Win->Render();
  const auto native = ReadRGB(s.Win);
  const int mx = MaxDifference(native, floats);
  std::cout << tag << ": atlas " << s.Mapper->GetAtlasScalarTypeName() << ", "
            << s.Mapper->GetAtlasBytesPerBrick() << " bytes a brick; max difference to float "
            << "storage " << mx << "\n";
  Check(s.Mapper->GetAtlasScalarTypeName() == std::string(c.AtlasType),
    tag + ": the atlas is " + c.AtlasType);
  Check(s.Mapper->GetAtlasBytesPerBrick() == 16 * 16 * 16 * c.TexelBytes,
    tag + ": a brick takes 16^3 texels of its type");
  Check(mx <= c.MaxToFloat,
    tag + ": the native image equals float storage's (max <= " + Of255(c.MaxToFloat) + ")");
  Check(s.Mapper->GetShaderSource(1).find("uDecode0") != std::string::npos,
    tag + ": the normalised atlas is decoded");
  ok = CheckVolumeComparison(s.Compare(tag), tag, 0.4, 2, 3000) && ok;

  // One budget of 4 float bricks (0.0625 MiB): 16 slots of uint8, 8 of 16-bit bricks.
  const double budget = 4 * 16.0 * 16 * 16 * 4 / (1024.0 * 1024.0);
  s.Mapper->SetAtlasBudget(budget);
  s.Win->Render();
  const int slots = s.Mapper->GetNumberOfAtlasSlots();
  s.Mapper->SetScalarStorage(Storages::Float32);
  s.Win->Render();
  const int floatSlots = s.Mapper->GetNumberOfAtlasSlots();
  std::cout << tag << ": " << budget << " MiB hold " << slots << " native bricks, " << floatSlots
            << " float ones\n";
  Check(floatSlots == 4 && slots == 4 * 4 / c.TexelBytes,
    tag + ": the budget holds 4 / texel bytes times the float bricks");
  s.Mapper->SetScalarStorage(c.Storage);
  s.Mapper->SetAtlasBudget(256.0);

  // Plain textures (no atlas), native against float.
  s.Mapper->UseBrickAtlasOff();
  s.Win->Render();
  const auto plainNative = ReadRGB(s.Win);
  s.Mapper->SetScalarStorage(Storages::Float32);
  s.Win->Render();
  const auto plainFloat = ReadRGB(s.Win);
  s.Mapper->SetScalarStorage(c.Storage);
  s.Mapper->UseBrickAtlasOn();
  const int plainMax = MaxDifference(plainNative, plainFloat);
  std::cout << tag << ": plain textures, max difference native to float " << plainMax
            << ", to the native atlas " << MaxDifference(plainNative, native) << "\n";
  Check(plainMax <= c.MaxToFloat,
    tag + ": a native plain texture equals a float one (max <= " + Of255(c.MaxToFloat) + ")");
  // The atlas and the plain texture: two programs (FragmentKey::Atlas).
  Check(MaxDifference(plainNative, native) <= ImagePolicy::TwoProgramsMax,
    tag + ": the atlas equals the plain texture");

  // Paged from a pool of the same type.
  const std::string pool = paths.Output + "/lean-atlas-" + c.Name + ".spp";
  auto reader = WritePagedTwin(image, pool, 16);
  s.Mapper->SetInputConnection(0, reader->GetOutputPort());
  const bool converged = RenderUntilConverged(s) > 0;
  const auto paged = ReadRGB(s.Win);
  const int pagedMax = MaxDifference(paged, native);
  std::cout << tag << ": paged, atlas " << s.Mapper->GetAtlasScalarTypeName() << ", converged "
            << converged << ", max difference to in core " << pagedMax << "\n";
  Check(converged, tag + ": the paged volume converges");
  Check(s.Mapper->GetAtlasScalarTypeName() == std::string(c.AtlasType),
    tag + ": the paged atlas is " + c.AtlasType);
  // Paged vs in core: two programs (the paged one has the feedback code).
  Check(pagedMax <= ImagePolicy::TwoProgramsMax, tag + ": paged equals in core (max <= 1)");
}

/// A uint8 and an int16 volume overlapping: one R16 atlas; float data: R32F, no decode.
void MixedTypes(const TestPaths& paths, bool& ok)
{
  VolumeScene s(paths.Output);
  auto a = Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1);
  auto b = Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2);
  s.Add(Typed(a, VTK_UNSIGNED_CHAR, 1.0, 0.0), TypedProperty(0, 1.0, 0.0));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Typed(b, VTK_SHORT, 250.0, -28000.0), TypedProperty(1, 250.0, -28000.0), t);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
  s.Mapper->SetBrickSize(16);
  s.Mapper->SetScalarStorage(vtkMultiVolumeRayCastMapper::ScalarStorages::Native);
  s.Win->Render();
  const auto native = ReadRGB(s.Win);
  const std::string type = s.Mapper->GetAtlasScalarTypeName();
  s.Mapper->SetScalarStorage(vtkMultiVolumeRayCastMapper::ScalarStorages::Float32);
  s.Win->Render();
  const auto floats = ReadRGB(s.Win);
  const bool floatDecodes = s.Mapper->GetShaderSource(2).find("uDecode") != std::string::npos;
  s.Mapper->SetScalarStorage(vtkMultiVolumeRayCastMapper::ScalarStorages::Native);
  s.Win->Render();
  const int mx = MaxDifference(native, floats);
  std::cout << "LeanAtlas-mixed: uint8 and int16 in a " << type
            << " atlas; max difference to float storage " << mx << "\n";
  Check(type == "uint16", "uint8 and int16 volumes share an R16 atlas");
  // Native vs float storage: two programs (the decode), ImagePolicy::TwoProgramsMax.
  Check(mx <= ImagePolicy::TwoProgramsMax, "the mixed scene equals float storage (max <= 1)");
  Check(!floatDecodes, "float storage compiles no decode");
  ok = CheckVolumeComparison(s.Compare("LeanAtlas-mixed"), "LeanAtlas-mixed", 0.4, 2, 3000) && ok;

  // A float volume beside them: the atlas is float again.
  VolumeScene f(paths.Output);
  f.Add(a, MakeVolumeProperty(0));
  f.Add(Typed(b, VTK_UNSIGNED_CHAR, 1.0, 0.0), TypedProperty(1, 1.0, 0.0), t);
  f.UseMultiVolume();
  f.Camera(pos, foc);
  f.Mapper->SetBrickSize(16);
  f.Mapper->SetScalarStorage(vtkMultiVolumeRayCastMapper::ScalarStorages::Native);
  f.Win->Render();
  std::cout << "LeanAtlas-mixed: float and uint8 in a " << f.Mapper->GetAtlasScalarTypeName()
            << " atlas\n";
  Check(f.Mapper->GetAtlasScalarTypeName() == std::string("float32"),
    "a float volume keeps the shared atlas float");
}
}

int TestMultiVolumeLeanAtlas(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  for (const TypedCase& c : Cases)
    TypedVolume(c, paths, ok);
  MixedTypes(paths, ok);
  ok = ok && Failures() == 0;
  return CaseResult(ok, output);
}
