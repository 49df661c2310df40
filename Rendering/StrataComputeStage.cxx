// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataComputeStage.h"

#include "StrataShaderCache.h"
#include "vtkMatrix4x4.h"
#include "vtkObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

namespace strata
{
namespace
{
void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  strata::ShaderCache<int>::Replace(source, tag, code);
}

std::string OutputName(int i)
{
  return "uStrataOutput" + std::to_string(i);
}

// What replaces the fragment template's output declarations: the work group, the rectangle,
// the fragment built-ins as globals, and the output images.
std::string Declarations(const ComputeStage::Outputs& outputs)
{
  std::ostringstream dec;
  dec << "layout(local_size_x = " << ComputeStage::LocalSize
      << ", local_size_y = " << ComputeStage::LocalSize << ") in;\n"
      << "// Compute stage (strata::ComputeStage): one invocation per pixel of uStrataRect.\n"
      << "uniform ivec4 uStrataRect;       // target pixels dispatched: x, y, width, height\n"
      << "uniform ivec2 uStrataOrigin;     // window position of target pixel (0, 0)\n"
      << "uniform vec3 uStrataDepthRange;  // glDepthRange: near, far, far - near\n"
      << "vec4 strataFragCoord = vec4(0.0);\n"
      << "float strataFragDepth = 0.0;\n"
      << "bool strataDiscarded = false;\n"
      << "vec4 strataFragData[" << outputs.Count << "] = vec4[" << outputs.Count << "](";
  for (int i = 0; i < outputs.Count; ++i)
    dec << (i ? ", " : "") << "vec4(0.0)";
  dec << ");\n";
  const char* access =
    outputs.Staged || outputs.Blending == ComputeStage::Blend::None ? "writeonly " : "";
  for (int i = 0; i < outputs.Count; ++i)
    dec << "layout(binding = " << ComputeStage::FirstImageUnit + i << ", rgba32f) uniform "
        << access << "image2D " << OutputName(i) << ";\n";
  if (outputs.Staged)
    dec << "layout(binding = " << ComputeStage::DepthImageUnit(outputs)
        << ", rg32f) uniform writeonly image2D uStrataDepth; // depth, 1 where written\n";
  return dec.str();
}

std::string BlendOutput(const ComputeStage::Outputs& outputs, int i)
{
  const std::string name = OutputName(i);
  const std::string src = "strataFragData[" + std::to_string(i) + "]";
  switch (outputs.Blending)
  {
    case ComputeStage::Blend::FrontToBack:
      return "    {\n      vec4 dst = imageLoad(" + name + ", texel);\n      imageStore(" + name +
             ", texel, " + src + " * (1.0 - dst.a) + dst);\n    }\n";
    case ComputeStage::Blend::Over:
      return "    {\n      vec4 dst = imageLoad(" + name + ", texel);\n      imageStore(" + name +
             ", texel, " + src + " + dst * (1.0 - " + src + ".a));\n    }\n";
    default:
      return "    imageStore(" + name + ", texel, " + src + ");\n";
  }
}

// The compute main: the pixel, the fragment's main, its outputs.
std::string Main(const ComputeStage::Outputs& outputs)
{
  std::ostringstream main;
  main << "\nvoid main()\n{\n"
       << "  ivec2 local = ivec2(gl_GlobalInvocationID.xy);\n"
       << "  if (any(greaterThanEqual(local, uStrataRect.zw)))\n  {\n    return;\n  }\n"
       << "  ivec2 texel = uStrataRect.xy + local;\n"
       << "  strataFragCoord = vec4(vec2(texel + uStrataOrigin) + 0.5, 0.5, 1.0);\n"
       << "  strataFragDepth = 0.5;\n"
       << "  strataDiscarded = false;\n"
       << "  for (int i = 0; i < " << outputs.Count << "; ++i)\n  {\n"
       << "    strataFragData[i] = vec4(0.0);\n  }\n"
       << "  strataFragmentMain();\n";
  if (outputs.Staged)
    main << "  imageStore(uStrataDepth, texel, vec4(strataFragDepth, strataDiscarded ? 0.0 : 1.0, "
            "0.0, 0.0));\n";
  main << "  if (!strataDiscarded)\n  {\n";
  for (int i = 0; i < outputs.Count; ++i)
    main << BlendOutput(outputs, i);
  main << "  }\n}\n";
  return main.str();
}

// Program and shader objects of the probe, deleted on every path.
struct ProbeObjects
{
  GLuint Texture = 0, Framebuffer = 0, Array = 0, Draw = 0, Dispatch = 0;
  ~ProbeObjects()
  {
    glDeleteProgram(this->Draw);
    glDeleteProgram(this->Dispatch);
    glDeleteVertexArrays(1, &this->Array);
    glDeleteFramebuffers(1, &this->Framebuffer);
    glDeleteTextures(1, &this->Texture);
  }
};

GLuint ProbeProgram(const char* vertex, const char* fragmentOrCompute)
{
  const GLuint program = glCreateProgram();
  const GLenum types[2] = { GL_VERTEX_SHADER,
    static_cast<GLenum>(vertex ? GL_FRAGMENT_SHADER : GL_COMPUTE_SHADER) };
  const char* sources[2] = { vertex, fragmentOrCompute };
  for (int s = 0; s < 2; ++s)
  {
    if (!sources[s])
      continue;
    const GLuint shader = glCreateShader(types[s]);
    glShaderSource(shader, 1, &sources[s], nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
    glDeleteShader(shader);
  }
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

// The probe's kernel: dependent multiply-adds per pixel, their count a uniform so that no
// compiler folds the loop; the same in both stages.
const char* ProbeVertex = "#version 430 core\n"
                          "void main()\n{\n"
                          "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, "
                          "float((gl_VertexID & 2) << 1) - 1.0);\n"
                          "  gl_Position = vec4(p, 0.0, 1.0);\n}\n";
const char* ProbeFragment = "#version 430 core\n"
                            "uniform int uIterations;\n"
                            "out vec4 color;\n"
                            "void main()\n{\n"
                            "  float x = gl_FragCoord.x * 1.0e-3 + gl_FragCoord.y * 1.0e-6;\n"
                            "  for (int i = 0; i < uIterations; ++i)\n  {\n"
                            "    x = x * 0.99991 + 0.00013;\n  }\n"
                            "  color = vec4(x);\n}\n";
const char* ProbeCompute = "#version 430 core\n"
                           "layout(local_size_x = 8, local_size_y = 8) in;\n"
                           "layout(binding = 0, rgba8) uniform writeonly image2D uTarget;\n"
                           "uniform int uIterations;\n"
                           "void main()\n{\n"
                           "  vec2 p = vec2(gl_GlobalInvocationID.xy) + 0.5;\n"
                           "  float x = p.x * 1.0e-3 + p.y * 1.0e-6;\n"
                           "  for (int i = 0; i < uIterations; ++i)\n  {\n"
                           "    x = x * 0.99991 + 0.00013;\n  }\n"
                           "  imageStore(uTarget, ivec2(gl_GlobalInvocationID.xy), vec4(x));\n}\n";

constexpr int ProbeSize = 256;
constexpr int ProbeIterations = 256;
constexpr int ProbeRuns = 4;

// The best of three timings (ms) of ProbeRuns kernels, by the wall clock around glFinish.
template<typename Run>
double BestOf(Run&& run)
{
  run();
  glFinish();
  double best = 1e300;
  for (int k = 0; k < 3; ++k)
  {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < ProbeRuns; ++r)
      run();
    glFinish();
    const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
    best = std::min(best, took.count() / ProbeRuns);
  }
  return best;
}

bool MeasureProbe(vtkOpenGLRenderWindow* window, ComputeStage::ProbeResult& result)
{
  vtkOpenGLState* state = window->GetState();
  ProbeObjects o;
  o.Draw = ProbeProgram(ProbeVertex, ProbeFragment);
  o.Dispatch = ProbeProgram(nullptr, ProbeCompute);
  if (!o.Draw || !o.Dispatch)
    return false;
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  const int unit = units->Allocate();
  state->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glGenTextures(1, &o.Texture);
  glBindTexture(GL_TEXTURE_2D, o.Texture);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, ProbeSize, ProbeSize);
  glBindTexture(GL_TEXTURE_2D, 0);
  units->Free(unit);
  glGenVertexArrays(1, &o.Array);
  glGenFramebuffers(1, &o.Framebuffer);

  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissorSaver(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, o.Framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, o.Texture, 0);
  state->vtkglDrawBuffer(GL_COLOR_ATTACHMENT0);
  state->vtkglViewport(0, 0, ProbeSize, ProbeSize);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  window->GetShaderCache()->ReleaseCurrentShader();

  glUseProgram(o.Draw);
  glUniform1i(glGetUniformLocation(o.Draw, "uIterations"), ProbeIterations);
  glBindVertexArray(o.Array);
  result.FragmentMs = BestOf([] { glDrawArrays(GL_TRIANGLES, 0, 3); });
  glBindVertexArray(0);

  glUseProgram(o.Dispatch);
  glUniform1i(glGetUniformLocation(o.Dispatch, "uIterations"), ProbeIterations);
  glBindImageTexture(0, o.Texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  const GLuint groups = ProbeSize / 8;
  result.ComputeMs = BestOf(
    [groups]
    {
      glDispatchCompute(groups, groups, 1);
      // Each run writes what the one before wrote, as the fragment runs do in order.
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    });
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glUseProgram(0);
  state->PopFramebufferBindings();
  return true;
}

std::mutex ProbeMutex;
std::map<std::string, ComputeStage::ProbeResult>& Probes()
{
  static std::map<std::string, ComputeStage::ProbeResult> probes;
  return probes;
}
int ProbeCount = 0;
}

std::string ComputeStage::FromFragment(const std::string& fragment,
  const Outputs& outputs,
  std::string& error)
{
  const std::string mainSignature = "void main()";
  const size_t mainAt = fragment.find(mainSignature);
  if (mainAt == std::string::npos || fragment.find(mainSignature, mainAt + 1) != std::string::npos)
  {
    error = "the fragment source has no single main()";
    return std::string();
  }
  const size_t discardAt = fragment.find("discard;");
  if (discardAt != std::string::npos && discardAt < mainAt)
  {
    error = "a discard outside main() cannot become a return";
    return std::string();
  }
  for (const char* input : { "\nin ", "\nvarying ", "\nflat in " })
    if (fragment.find(input) != std::string::npos)
    {
      error = "the fragment source reads an input varying";
      return std::string();
    }
  if (fragment.find("//VTK::System::Dec") != 0 ||
      fragment.find("//VTK::Output::Dec") == std::string::npos)
  {
    error = "the fragment source lacks VTK's system or output tag";
    return std::string();
  }
  std::string cs = fragment;
  Replace(cs, "//VTK::System::Dec", "#version 430 core");
  Replace(cs, "//VTK::Output::Dec", Declarations(outputs));
  Replace(cs, mainSignature, "void strataFragmentMain()");
  Replace(cs, "discard;", "{\n    strataDiscarded = true;\n    return;\n  }");
  Replace(cs, "gl_FragData[", "strataFragData[");
  Replace(cs, "gl_FragDepth", "strataFragDepth");
  Replace(cs, "gl_FragCoord", "strataFragCoord");
  Replace(cs, "gl_DepthRange.near", "uStrataDepthRange.x");
  Replace(cs, "gl_DepthRange.far", "uStrataDepthRange.y");
  Replace(cs, "gl_DepthRange.diff", "uStrataDepthRange.z");
  for (const char* builtin :
    { "gl_Frag", "gl_DepthRange", "gl_PointCoord", "gl_FrontFacing", "dFdx", "dFdy", "fwidth" })
    if (cs.find(builtin) != std::string::npos)
    {
      error = std::string("the fragment source uses ") + builtin + ", which compute shaders lack";
      return std::string();
    }
  cs += Main(outputs);
  return cs;
}

bool ComputeStage::ScreenRect(vtkMatrix4x4* toClip,
  const double* points,
  int count,
  const int size[2],
  double dilate,
  int rect[4])
{
  double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
  bool whole = count == 0;
  for (int i = 0; i < count && !whole; ++i)
  {
    const double p[4] = { points[3 * i], points[3 * i + 1], points[3 * i + 2], 1.0 };
    double c[4];
    toClip->MultiplyPoint(p, c);
    // At or behind the eye (w <= 0) the projection folds: take the whole viewport.
    if (!(c[3] > 1e-12 * (std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + 1e-30)))
    {
      whole = true;
      break;
    }
    for (int a = 0; a < 2; ++a)
    {
      const double pixel = (c[a] / c[3] * 0.5 + 0.5) * size[a];
      lo[a] = std::min(lo[a], pixel);
      hi[a] = std::max(hi[a], pixel);
    }
  }
  for (int a = 0; a < 2; ++a)
  {
    const double l = whole ? 0.0 : std::max(0.0, std::floor(lo[a] - dilate - 1.0));
    const double h = whole ? size[a] : std::min(double(size[a]), std::ceil(hi[a] + dilate + 1.0));
    rect[a] = static_cast<int>(l);
    rect[2 + a] = h > l ? static_cast<int>(h - l) : 0;
  }
  return rect[2] > 0 && rect[3] > 0;
}

void ComputeStage::Dispatch(vtkShaderProgram* program, const int rect[4], const int origin[2])
{
  glUniform4i(program->FindUniform("uStrataRect"), rect[0], rect[1], rect[2], rect[3]);
  glUniform2i(program->FindUniform("uStrataOrigin"), origin[0], origin[1]);
  float range[2] = { 0.0f, 1.0f };
  glGetFloatv(GL_DEPTH_RANGE, range);
  glUniform3f(program->FindUniform("uStrataDepthRange"), range[0], range[1], range[1] - range[0]);
  glDispatchCompute(static_cast<GLuint>((rect[2] + LocalSize - 1) / LocalSize),
    static_cast<GLuint>((rect[3] + LocalSize - 1) / LocalSize),
    1);
}

int ComputeStage::GetMaxImageUnits(vtkOpenGLRenderWindow*)
{
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 3))
    return 0;
  GLint units = 0, uniforms = 0;
  glGetIntegerv(GL_MAX_IMAGE_UNITS, &units);
  glGetIntegerv(GL_MAX_COMPUTE_IMAGE_UNIFORMS, &uniforms);
  return std::min(units, uniforms);
}

ComputeStage::ProbeResult ComputeStage::Probe(vtkOpenGLRenderWindow* window)
{
  const GLubyte* name = glGetString(GL_RENDERER);
  const std::string renderer = name ? reinterpret_cast<const char*>(name) : "unknown";
  std::lock_guard<std::mutex> lock(ProbeMutex);
  auto it = Probes().find(renderer);
  if (it != Probes().end())
    return it->second;
  ProbeResult result;
  result.Renderer = renderer;
  if (GetMaxImageUnits(window) > 0)
    result.Measured = MeasureProbe(window, result);
  ++ProbeCount;
  Probes()[renderer] = result;
  return result;
}

int ComputeStage::GetNumberOfProbes()
{
  std::lock_guard<std::mutex> lock(ProbeMutex);
  return ProbeCount;
}

int ComputeStage::Choose(vtkOpenGLRenderWindow* window, int requested, int images)
{
  return Choose(window, requested, images, GetMaxImageUnits(window));
}

int ComputeStage::Choose(vtkOpenGLRenderWindow* window, int requested, int images, int units)
{
  if (units == 0 || images > units || requested == Fragment)
    return Fragment;
  if (requested == Compute)
    return Compute;
  const ProbeResult probe = Probe(window);
  return probe.Measured && probe.ComputeMs < probe.FragmentMs ? Compute : Fragment;
}

int ComputeStage::Choice::Choose(vtkObject* mapper,
  vtkOpenGLRenderWindow* window,
  int requested,
  int images)
{
  if (window != this->Window)
  {
    this->Window = window;
    this->Units = GetMaxImageUnits(window);
  }
  const int stage = ComputeStage::Choose(window, requested, images, this->Units);
  if (requested == Compute && stage != requested && !this->Warned)
  {
    vtkWarningWithObjectMacro(mapper,
      "The compute stage needs OpenGL 4.3 and " << images
                                                << " image units here: ray casting in fragment "
                                                   "shaders.");
    this->Warned = true;
  }
  if (requested == Auto)
    this->ProbeRatio = Probe(window).Ratio();
  this->InUse = stage;
  return stage;
}

int ComputeStage::DefaultStage()
{
  const char* value = std::getenv("STRATA_RAY_CASTING_STAGE");
  if (!value)
    return Auto;
  std::string v(value);
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  return v == "fragment" ? Fragment : (v == "compute" ? Compute : Auto);
}

const char* ComputeStage::StageName(int stage)
{
  return stage == Fragment ? "Fragment" : (stage == Compute ? "Compute" : "Auto");
}
}
