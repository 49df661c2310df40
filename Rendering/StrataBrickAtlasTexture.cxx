// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataBrickAtlasTexture.h"

#include "StrataRenderUtilities.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include <cmath>

#include "vtkMultiVolumeAtlasLookup.h"

namespace strata
{

std::string BrickAtlasTexture::GetShaderDeclarations()
{
  return "uniform sampler3D uAtlas;\nuniform vec3 uAtlasSize; // texels\n"
         "uniform float uBrickSize;\n";
}

std::string BrickAtlasTexture::GetLookupFunction(int n,
  const std::string& feedbackCheck,
  bool normalized)
{
  return GetLookupFunction(std::to_string(n), feedbackCheck, normalized);
}

std::string BrickAtlasTexture::GetLookupFunction(const std::string& n,
  const std::string& feedbackCheck,
  bool normalized)
{
  std::string code = vtkMultiVolumeAtlasLookup;
  // Feedback wants the level-0 brick and how coarse its node is (2^level; a transparent brick
  // as coarse as can be, a slotless one 0).
  const std::string feedback =
    feedbackCheck.empty()
      ? std::string()
      : "ivec3 b = min(ivec3(x / (uBrickSize - 1.0)), ivec3(uTableDims@n@) - 1);\n"
        "  float coarse = f.w > 0.0 ? 1.0 / f.w : (f.w > -1.5 ? 3.0e38 : 0.0);\n  " +
          feedbackCheck;
  vtkShaderProgram::Substitute(code, "//STRATA::FeedbackCheck::Impl", feedback, true);
  vtkShaderProgram::Substitute(code,
    "//STRATA::Decode::Dec",
    normalized ? "uniform vec2 uDecode@n@; // value = texel x + y (strata::BrickAtlasFormat)" : "",
    true);
  vtkShaderProgram::Substitute(
    code, "@decode@", normalized ? " * uDecode@n@.x + uDecode@n@.y" : "", true);
  vtkShaderProgram::Substitute(code, "@n@", n, true);
  return code;
}

namespace
{
// GL's internal format, format and type of an atlas of `type` texels.
void GetTexelFormat(strata::VolumeBrickTree::ScalarType type, GLint& internal, GLenum& pixelType)
{
  switch (type)
  {
    case strata::VolumeBrickTree::ScalarType::UInt8:
      internal = GL_R8;
      pixelType = GL_UNSIGNED_BYTE;
      return;
    case strata::VolumeBrickTree::ScalarType::UInt16:
    case strata::VolumeBrickTree::ScalarType::Int16:
      internal = GL_R16;
      pixelType = GL_UNSIGNED_SHORT;
      return;
    default:
      internal = GL_R32F;
      pixelType = GL_FLOAT;
  }
}
}

void BrickAtlasTexture::Allocate(const std::array<int, 3>& size,
  strata::VolumeBrickTree::ScalarType type)
{
  GLint internal = GL_R32F;
  GLenum pixelType = GL_FLOAT;
  GetTexelFormat(type, internal, pixelType);
  glBindTexture(GL_TEXTURE_3D, this->Atlas.Get());
  glTexImage3D(
    GL_TEXTURE_3D, 0, internal, size[0], size[1], size[2], 0, GL_RED, pixelType, nullptr);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_3D, 0);
  this->Size = size;
  this->Type = type;
}

void BrickAtlasTexture::BeginUploads()
{
  glBindTexture(GL_TEXTURE_3D, this->Atlas.GetName());
  // Put back at EndUploads (strata::RenderUtilities::ScopedPixelStore says why).
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &this->SavedAlignment);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
}

void BrickAtlasTexture::UploadBrick(const std::array<int, 3>& slot,
  int brickSize,
  const void* texels)
{
  GLint internal = GL_R32F;
  GLenum pixelType = GL_FLOAT;
  GetTexelFormat(this->Type, internal, pixelType);
  const int B = brickSize;
  glTexSubImage3D(
    GL_TEXTURE_3D, 0, slot[0] * B, slot[1] * B, slot[2] * B, B, B, B, GL_RED, pixelType, texels);
}

void BrickAtlasTexture::EndUploads()
{
  glBindTexture(GL_TEXTURE_3D, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, this->SavedAlignment);
}

void BrickAtlasTexture::SetIndex(int key,
  const int bricks[3],
  int brickSize,
  const std::vector<uint16_t>& table)
{
  auto it = this->Index.find(key);
  if (it == this->Index.end())
    it = this->Index.emplace(key, strata::GLObject::Kinds::Texture).first;
  // Entry of level-0 brick b covered by node (level w, slot e): the atlas texel of index x is
  // e B + 0.5 + (x 2^-w - (b >> w) S), i.e. origin + x 2^-w, in texels (origin and scale are
  // exact in float; the shader normalises after the one rounding of their sum).
  const size_t n = table.size() / 4;
  std::vector<float> entries(4 * n);
  const int S = brickSize - 1;
  for (int k = 0, i = 0; k < bricks[2]; ++k)
    for (int j = 0; j < bricks[1]; ++j)
      for (int l = 0; l < bricks[0]; ++l, ++i)
      {
        const uint16_t* e = &table[4 * size_t(i)];
        float* out = &entries[4 * size_t(i)];
        const int b[3] = { l, j, k };
        if (e[3] >= 65534)
        {
          out[0] = out[1] = out[2] = 0.0f;
          out[3] = e[3] == 65534 ? -1.0f : -2.0f;
          continue;
        }
        for (int a = 0; a < 3; ++a)
          out[a] = static_cast<float>(double(e[a]) * brickSize - double(b[a] >> e[3]) * S + 0.5);
        out[3] = static_cast<float>(std::ldexp(1.0, -int(e[3])));
      }
  glBindTexture(GL_TEXTURE_3D, it->second.Get());
  const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 4);
  glTexImage3D(GL_TEXTURE_3D,
    0,
    GL_RGBA32F,
    bricks[0],
    bricks[1],
    bricks[2],
    0,
    GL_RGBA,
    GL_FLOAT,
    entries.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  // Lookups at the volume's far faces land on the table's edge, never wrap to its start.
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_3D, 0);
}

unsigned int BrickAtlasTexture::GetIndexName(int key) const
{
  auto it = this->Index.find(key);
  return it == this->Index.end() ? 0 : it->second.GetName();
}

void BrickAtlasTexture::ReleaseGraphicsResources()
{
  this->Atlas.Release();
  for (auto& i : this->Index)
    i.second.Release();
  this->Index.clear();
  this->Size = { 0, 0, 0 };
  this->Type = strata::VolumeBrickTree::ScalarType::Float32;
}
}
