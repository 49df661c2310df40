// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "ShaderSource" of the multi-volume ray caster, compared pixel by pixel with the
// double-precision reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

int TestMultiVolumeShaderSource(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  using namespace strata_test;
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Only what a fragment needs: a fragment of one post-classified volume samples one volume
  // and reads no pre-integration table; one covered by two samples both; pre-integration
  // replaces the per-sample lookups; back-to-front has no early termination.
  VolumeScene s(paths.Output);
  s.Add(Blob(20, 20, 20, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
  s.Add(Blob(20, 20, 20, 1.0, 1.0, 1.0, 10, 0, 0, 2), MakeVolumeProperty(1));
  s.UseMultiVolume();
  const double pos[3] = { -40, -60, 50 }, foc[3] = { 15, 10, 10 };
  s.Camera(pos, foc);
  s.Win->Render();
  const std::string one = s.Mapper->GetShaderSource(1);
  const std::string two = s.Mapper->GetShaderSource(2);
  auto has = [](const std::string& src, const char* what)
  { return src.find(what) != std::string::npos; };
  std::cout << "ShaderSource: " << s.Mapper->GetNumberOfFragments()
            << " fragments; 1-volume shader " << one.size() << " chars, 2-volume shader "
            << two.size() << " chars\n";
  Check(!one.empty() && !two.empty(), "shaders for 1 and 2 volumes were generated");
  Check(has(one, "strataScalarAt0") && !has(one, "strataScalarAt1"),
    "1-volume shader samples exactly one volume");
  Check(has(two, "strataScalarAt1") && !has(two, "strataScalarAt2"),
    "2-volume shader samples exactly two");
  Check(has(one, "uAtlas") && has(one, "uIndex0"),
    "bricked volumes are read through their index texture and the atlas");
  Check(!has(one, "uPreTable") && !has(one, "strataPair"),
    "post-classification has no pre-integration code");
  Check(!has(one, "uAccumulation") || has(one, "uTerminationOpacity"),
    "early termination only with its threshold");
  Check(!has(one, "ormal") && !has(one, "radient"), "unshaded: no gradient or normal code");
  s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PreIntegrated);
  s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
  s.Win->Render();
  const std::string pre = s.Mapper->GetShaderSource(1);
  Check(has(pre, "uPreTable0") && !has(pre, "uTransfer0"),
    "pre-integrated shader reads the table, not the TF");
  // The stage the frames ran in: its own entry point and output, and nothing of the other.
  const bool compute = s.Mapper->GetStageInUse() == vtkMultiVolumeRayCastMapper::Stages::Compute;
  std::cout << "ShaderSource: frames ran in the " << s.Mapper->GetStageInUseAsString()
            << " stage\n";
  for (const std::string* src : { &one, &two, &pre })
    Check(compute ? has(*src, "layout(local_size_x") && !has(*src, "gl_Frag")
                  : has(*src, "gl_FragData[0]") && !has(*src, "gl_GlobalInvocationID"),
      "the source is the stage's own");
  Check(!compute || (has(one, "strataFragData[0] * (1.0 - dst.a) + dst") &&
                      has(pre, "strataFragData[0] + dst * (1.0 - strataFragData[0].a)")),
    "compute: front to back blends under, back to front over");
  Check(!has(pre, "uTerminationOpacity"), "back-to-front: no early termination code");
  // Level-of-detail feedback exists only where something is paged: in-core scenes carry no
  // image load/store, no extension line and no feedback lookups.
  // (The compute stage stores its outputs with imageStore into uStrataOutput<r>: those only.)
  auto feedbackStores = [](const std::string& src)
  {
    int n = 0;
    for (size_t at = src.find("imageStore("); at != std::string::npos;
         at = src.find("imageStore(", at + 1))
      n += src.compare(at + 11, 13, "uStrataOutput") != 0 ? 1 : 0;
    return n;
  };
  for (const std::string* src : { &one, &two, &pre })
    Check(!has(*src, "#extension") && !has(*src, "uFeedback") && !has(*src, "gLack") &&
            !has(*src, "imageAtomic") && feedbackStores(*src) == 0,
      "in core: no feedback code");
  // The same two volumes paged from pools: the shaders report the costliest lacking brick
  // of the feedback rays (fragments compare through the score image; front to back the
  // nearer wins a tie); with LevelOfDetailThreshold 0 level 0 is wanted everywhere, so there is
  // no footprint code.
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  for (int i = 0; i < 2; ++i)
  {
    const std::string pool = paths.Output + "/shader-source-" + std::to_string(i) + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(s.Images[i]);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(8);
    writer->Write();
    readers.push_back(vtkSmartPointer<vtkPagePoolReader>::New());
    readers.back()->SetFileName(pool.c_str());
    s.Mapper->SetInputConnection(i, readers.back()->GetOutputPort());
  }
  s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PostClassification);
  s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::FrontToBack);
  s.Win->Render();
  const std::string paged = s.Mapper->GetShaderSource(2);
  Check(has(paged, "#extension GL_ARB_shader_image_load_store : require") &&
          has(paged, "gLackVolume = better ? 1") && !has(paged, "uFeedbackSet2") &&
          has(paged, "gLackScore > imageLoad(uFeedbackScore") &&
          has(paged, "imageStore(uFeedback, texel") && has(paged, "strataPackPage") &&
          !has(paged, "gFootprint"),
    "paged: the 2-volume shader reports lacking bricks of both volumes into the feedback image");
  s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
  s.Win->Render();
  const std::string pagedBack = s.Mapper->GetShaderSource(1);
  Check(has(pagedBack, "gLackScore >= imageLoad(uFeedbackScore") &&
          !has(pagedBack, "gTransmittance = (1.0 - prior)"),
    "paged, back to front: on equal cost the nearer (later) report wins; no transmittance is "
    "known");
  s.Mapper->LevelOfDetailFeedbackOff();
  s.Win->Render();
  const std::string pagedOff = s.Mapper->GetShaderSource(1);
  Check(!pagedOff.empty() && !has(pagedOff, "#extension") && !has(pagedOff, "uFeedback"),
    "paged with feedback off: no feedback code");
  for (int i = 0; i < 2; ++i)
    std::remove((paths.Output + "/shader-source-" + std::to_string(i) + ".spp").c_str());
  ok = Failures() == 0;
  return CaseResult(ok, output);
}
