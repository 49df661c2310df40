// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeFragmentGeometry.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

namespace strata
{

void VolumeFragmentGeometry::Update(const std::vector<vtkMatrix4x4*>& indexToWorld,
  const std::vector<const int*>& dims)
{
  std::vector<strata::VolumeBSPTree::Box> boxes;
  for (size_t v = 0; v < indexToWorld.size(); ++v)
  {
    vtkNew<vtkMatrix4x4> unitToIndex;
    for (int a = 0; a < 3; ++a)
    {
      const bool thin = dims[v][a] == 1;
      unitToIndex->SetElement(a, a, thin ? 1.0 : dims[v][a] - 1.0);
      unitToIndex->SetElement(a, 3, thin ? -0.5 : 0.0);
    }
    vtkNew<vtkMatrix4x4> unitToWorld;
    vtkMatrix4x4::Multiply4x4(indexToWorld[v], unitToIndex, unitToWorld);
    strata::VolumeBSPTree::Box box;
    std::copy(unitToWorld->GetData(), unitToWorld->GetData() + 16, box.Matrix.begin());
    box.VolumeId = static_cast<int>(v);
    boxes.push_back(box);
  }
  if (this->Tree.SetBoxes(boxes))
  {
    this->Valid = false;
  }
  this->Tree.Update();
  if (!this->Valid)
  {
    this->Upload();
  }
}

void VolumeFragmentGeometry::Upload()
{
  const int fragments = this->Tree.GetNumberOfFragments();
  std::vector<float> verts;
  this->First.assign(fragments, 0);
  this->Count.assign(fragments, 0);
  this->Centroid.assign(fragments, { 0.f, 0.f, 0.f });
  this->Planes.assign(fragments, {});
  for (int f = 0; f < fragments; ++f)
  {
    const auto& frag = this->Tree.GetFragment(f);
    this->First[f] = static_cast<int>(verts.size() / 3);
    for (int idx : frag.Triangles)
      for (int a = 0; a < 3; ++a)
        verts.push_back(static_cast<float>(frag.Vertices[idx][a]));
    this->Count[f] = static_cast<int>(frag.Triangles.size());
    for (const auto& vtx : frag.Vertices)
      for (int c = 0; c < 3; ++c)
        this->Centroid[f][c] += static_cast<float>(vtx[c] / frag.Vertices.size());
    for (const auto& plane : frag.Planes)
      for (int c = 0; c < 4; ++c)
        this->Planes[f].push_back(static_cast<float>(plane[c]));
  }
  glBindBuffer(GL_ARRAY_BUFFER, this->Vertices.Get());
  glBufferData(GL_ARRAY_BUFFER, verts.size() * sizeof(float), verts.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  this->ArrayProgram = nullptr;
  this->Valid = true;
}

void VolumeFragmentGeometry::Bind(vtkShaderProgram* program)
{
  glBindVertexArray(this->VertexArray.Get());
  if (this->ArrayProgram != program)
  {
    glBindBuffer(GL_ARRAY_BUFFER, this->Vertices.GetName());
    const GLint location = glGetAttribLocation(program->GetHandle(), "vertexLocal");
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    this->ArrayProgram = program;
  }
}

void VolumeFragmentGeometry::Draw(int f) const
{
  glDrawArrays(GL_TRIANGLES, this->First[f], this->Count[f]);
}

void VolumeFragmentGeometry::Unbind() const
{
  glBindVertexArray(0);
}

void VolumeFragmentGeometry::ReleaseGraphicsResources()
{
  this->Vertices.Release();
  this->VertexArray.Release();
  this->ArrayProgram = nullptr;
  this->Valid = false;
}
}
