// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkBrickAtlasTexture.h"

#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include "vtkMultiVolumeAtlasLookup.h"

std::string vtkBrickAtlasTexture::GetShaderDeclarations()
{
  return "uniform sampler3D uAtlas;\nuniform vec3 uAtlasSize; // texels\n"
         "uniform float uBrickSize;\n";
}

std::string vtkBrickAtlasTexture::GetLookupFunction(int n, const std::string& feedbackCheck)
{
  std::string code = vtkMultiVolumeAtlasLookup;
  vtkShaderProgram::Substitute(code, "@n@", std::to_string(n), true);
  vtkShaderProgram::Substitute(code, "//STRATA::FeedbackCheck::Impl", feedbackCheck, true);
  return code;
}

void vtkBrickAtlasTexture::Allocate(const std::array<int, 3>& size)
{
  glBindTexture(GL_TEXTURE_3D, this->Atlas.Get());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, size[0], size[1], size[2], 0, GL_RED, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_3D, 0);
  this->Size = size;
}

void vtkBrickAtlasTexture::BeginUploads()
{
  glBindTexture(GL_TEXTURE_3D, this->Atlas.GetName());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void vtkBrickAtlasTexture::UploadBrick(const std::array<int, 3>& slot,
  int brickSize,
  const float* values)
{
  const int B = brickSize;
  glTexSubImage3D(
    GL_TEXTURE_3D, 0, slot[0] * B, slot[1] * B, slot[2] * B, B, B, B, GL_RED, GL_FLOAT, values);
}

void vtkBrickAtlasTexture::EndUploads()
{
  glBindTexture(GL_TEXTURE_3D, 0);
}

void vtkBrickAtlasTexture::SetIndex(int key,
  const int bricks[3],
  const std::vector<uint16_t>& table)
{
  auto it = this->Index.find(key);
  if (it == this->Index.end())
    it = this->Index.emplace(key, vtkStrataGLObject::Kinds::Texture).first;
  glBindTexture(GL_TEXTURE_3D, it->second.Get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  glTexImage3D(GL_TEXTURE_3D,
    0,
    GL_RGBA16UI,
    bricks[0],
    bricks[1],
    bricks[2],
    0,
    GL_RGBA_INTEGER,
    GL_UNSIGNED_SHORT,
    table.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_3D, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

unsigned int vtkBrickAtlasTexture::GetIndexName(int key) const
{
  auto it = this->Index.find(key);
  return it == this->Index.end() ? 0 : it->second.GetName();
}

void vtkBrickAtlasTexture::ReleaseGraphicsResources()
{
  this->Atlas.Release();
  for (auto& i : this->Index)
    i.second.Release();
  this->Index.clear();
  this->Size = { 0, 0, 0 };
}
