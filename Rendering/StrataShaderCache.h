// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::ShaderCache
 * @brief   A mapper's compiled programs by typed feature key: a key's source is built once,
 *          handed to VTK's shader cache once, and from then on its program is bound directly.
 *
 * The composers of Strata's mappers (strata::MultiVolumeShaderComposer,
 * strata::HeightFieldShaderComposer, the hybrid's point shaders) key their programs by a struct of
 * exactly the features a draw uses (Key needs operator<). Ready() with a key seen before neither
 * builds a source nor hashes one (VTK's cache finds programs by the MD5 of their sources): it
 * binds the program it got the first time, compiling it again only when the window released
 * it. Counters let tests check that an unchanged frame builds and compiles nothing.
 *
 * Programs belong to the window's vtkOpenGLShaderCache; this cache only remembers them, so its
 * owner calls ReleaseGraphicsResources() whenever it releases its own resources (and a
 * program is asked for again when the window changes). Compute programs (the compute stage,
 * strata::ComputeStage) are not in VTK's cache: this cache owns them (vtkStrataComputeProgram)
 * and deletes them in ReleaseGraphicsResources().
 */
#ifndef StrataShaderCache_h
#define StrataShaderCache_h

#include "vtkOpenGLRenderWindow.h"   // For GetShaderCache
#include "vtkOpenGLShaderCache.h"    // For ReadyShaderProgram
#include "vtkShaderProgram.h"        // For GetCompiled, Substitute
#include "vtkSmartPointer.h"         // For vtkSmartPointer
#include "vtkStrataComputeProgram.h" // For the compute stage's programs

#include <map>    // For std::map
#include <string> // For std::string

namespace strata
{
template<typename Key>
class ShaderCache
{
public:
  struct Entry
  {
    std::string Vertex;
    std::string Fragment;
    vtkShaderProgram* Program = nullptr;
    vtkOpenGLRenderWindow* Window = nullptr;
  };

  /**
   * Binds the program of `key`, building its sources first with `build(key, vertex,
   * fragment)` if the key is new. Null (and an entry without program) when it does not compile.
   */
  template<typename Build>
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* window, const Key& key, Build&& build)
  {
    auto it = this->Entries.find(key);
    if (it == this->Entries.end())
    {
      Entry entry;
      build(key, entry.Vertex, entry.Fragment);
      ++this->SourcesBuilt;
      it = this->Entries.emplace(key, std::move(entry)).first;
    }
    Entry& e = it->second;
    vtkOpenGLShaderCache* cache = window->GetShaderCache();
    if (!e.Program || e.Window != window)
    {
      ++this->Compilations;
      e.Window = window;
      e.Program = cache->ReadyShaderProgram(e.Vertex.c_str(), e.Fragment.c_str(), "");
      return e.Program;
    }
    if (!e.Program->GetCompiled())
    {
      ++this->Compilations;
    }
    return cache->ReadyShaderProgram(e.Program, nullptr);
  }

  /// The entry of `key`, null if it was never built.
  const Entry* Find(const Key& key) const
  {
    auto it = this->Entries.find(key);
    return it == this->Entries.end() ? nullptr : &it->second;
  }

  /// A compute program (strata::ComputeStage) and its source.
  struct ComputeEntry
  {
    std::string Source;
    std::string Error; ///< why there is no program
    vtkSmartPointer<vtkStrataComputeProgram> Program;
    vtkOpenGLRenderWindow* Window = nullptr;
    bool Failed = false; ///< did not compile: not tried again
  };

  /**
   * Binds the compute program of `key`, building its source first with `build(key, source,
   * error)` if the key is new (an empty source: none, for the reason in error). Null when there is
   * none or it does not compile (the log in `error`).
   */
  template<typename Build>
  vtkStrataComputeProgram* ReadyCompute(vtkOpenGLRenderWindow* window,
    const Key& key,
    Build&& build,
    std::string& error)
  {
    auto it = this->ComputeEntries.find(key);
    if (it == this->ComputeEntries.end())
    {
      ComputeEntry entry;
      build(key, entry.Source, entry.Error);
      ++this->SourcesBuilt;
      it = this->ComputeEntries.emplace(key, std::move(entry)).first;
    }
    ComputeEntry& e = it->second;
    if (e.Source.empty() || e.Failed)
    {
      error = e.Error;
      return nullptr;
    }
    if (!e.Program || e.Window != window || !e.Program->IsBuilt())
    {
      ++this->Compilations;
      e.Window = window;
      e.Program = vtkSmartPointer<vtkStrataComputeProgram>::New();
      if (!e.Program->Build(e.Source))
      {
        e.Error = error = e.Program->GetError();
        e.Program = nullptr;
        e.Failed = true;
        return nullptr;
      }
    }
    e.Program->Use(window);
    return e.Program;
  }

  /// The compute entry of `key`, null if it was never built.
  const ComputeEntry* FindCompute(const Key& key) const
  {
    auto it = this->ComputeEntries.find(key);
    return it == this->ComputeEntries.end() ? nullptr : &it->second;
  }

  /// Sources built since construction (one per new key).
  int GetSourcesBuilt() const { return this->SourcesBuilt; }
  /// Programs handed to VTK's cache or recompiled since construction.
  int GetCompilations() const { return this->Compilations; }

  /// Forgets the programs (the window's shader cache owns them) and deletes the compute
  /// programs (their context current); the sources stay.
  void ReleaseGraphicsResources()
  {
    for (auto& e : this->Entries)
    {
      e.second.Program = nullptr;
      e.second.Window = nullptr;
    }
    for (auto& e : this->ComputeEntries)
    {
      if (e.second.Program)
        e.second.Program->ReleaseComputeProgram(e.second.Window);
      e.second.Program = nullptr;
      e.second.Window = nullptr;
    }
  }

  /// Replaces every occurrence of `tag` in `source` (vtkShaderProgram::Substitute).
  static void Replace(std::string& source, const std::string& tag, const std::string& code)
  {
    vtkShaderProgram::Substitute(source, tag, code, true);
  }

private:
  std::map<Key, Entry> Entries;
  std::map<Key, ComputeEntry> ComputeEntries;
  int SourcesBuilt = 0;
  int Compilations = 0;
};
}

#endif
