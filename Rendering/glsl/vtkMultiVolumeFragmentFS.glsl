//VTK::System::Dec
//STRATA::Extensions::Dec
// Strata multi-volume ray caster (Lux & Froehlich, multi-volume multi-resolution ray casting,
// section 3.4): one pass per convex BSP fragment, for exactly the volumes that cover it. The
// fragment's back faces are drawn; the ray's entry and exit come from the fragment's planes, so
// no exit-position buffer is needed. Samples lie on one lattice along the whole ray (t = k dt), and
// each lattice step is clipped to the fragment, so neighbouring fragments split the ray exactly.
// Overlapping media mix physically: extinctions add, emission is weighted by extinction.
// Tags are filled by vtkMultiVolumeRayCastMapper for the fragment's volume count and the scene's
// options; what a fragment does not use leaves no code here. With R rays per pixel, ray r writes
// gl_FragData[r], its own integration buffer, so each ray composites through all fragments on
// its own and the pixel is their mean. Paged scenes add level-of-detail feedback: the
// extension tag above, the lookups of lacking bricks and the report at the end of main.
// Every lookup is textureLod(..., 0.0) or texelFetch: the ray loop is non-uniform control flow,
// where the implicit derivatives of texture() are undefined.

//VTK::Output::Dec

uniform mat4 uClipToLocal;
uniform vec4 uViewport;      // window x, y, width, height of the renderer
uniform int uNumPlanes;
uniform vec4 uPlanes[64];    // inside: dot(n, p) + w <= 0, local frame
uniform float uSampleDistance; // world units between samples
uniform int uNumRegionPlanes; // 6 with a region (SetRegion), else 0
uniform vec4 uRegionPlanes[6]; // its faces, the same convention
uniform sampler2D uSceneDepth;

//STRATA::Surfaces::Dec

//STRATA::Volumes::Dec

//STRATA::Termination::Dec

//STRATA::Segment::Dec

// One ray through window position `pixel` across this fragment, its samples on the lattice
// t = (k + phase) dt. `prior`: the ray's opacity before this fragment; `tMin`: where to start
// (ray coherence). Returns the fragment's premultiplied composite; tFirst is the t of its first
// non-empty step (tExit if none), inside whether the ray meets the fragment at all.
vec4 strataCastRay(vec2 pixel, float phase, float prior, float tMin, out float tFirst, out bool inside)
{
  tFirst = 0.0;
  inside = false;
  vec2 ndc = (pixel - uViewport.xy) / uViewport.zw * 2.0 - 1.0;
  vec4 n4 = uClipToLocal * vec4(ndc, -1.0, 1.0);
  vec4 f4 = uClipToLocal * vec4(ndc, 1.0, 1.0);
  vec3 o = n4.xyz / n4.w;
  vec3 d = f4.xyz / f4.w - o;

  float tEnter = 0.0;
  float tExit = 1.0;
  for (int i = 0; i < uNumPlanes; ++i)
  {
    float denom = dot(uPlanes[i].xyz, d);
    float dist = dot(uPlanes[i].xyz, o) + uPlanes[i].w;
    if (denom < 0.0)
    {
      tEnter = max(tEnter, -dist / denom);
    }
    else if (denom > 0.0)
    {
      tExit = min(tExit, -dist / denom);
    }
    else if (dist > 0.0)
    {
      return vec4(0.0);
    }
  }
  // The region (a parallel process's box): clipped like by the fragment's own faces, on the
  // same lattice, anchored at the near plane in every process. The step across a face shared
  // with the next process's box is split there, as one process splits steps at every fragment
  // face; opaque geometry, cut to the same box, ends the rays at the same depths. (Moving the
  // faces to lattice points instead would let a ray run past the face into an opaque surface
  // that only the other process draws; Documentation/mpi.md gives the error it showed.)
  for (int i = 0; i < uNumRegionPlanes; ++i)
  {
    float denom = dot(uRegionPlanes[i].xyz, d);
    float dist = dot(uRegionPlanes[i].xyz, o) + uRegionPlanes[i].w;
    if (denom < 0.0)
    {
      tEnter = max(tEnter, -dist / denom);
    }
    else if (denom > 0.0)
    {
      tExit = min(tExit, -dist / denom);
    }
    else if (dist > 0.0)
    {
      return vec4(0.0);
    }
  }
  // Opaque geometry ends the ray: its depth, unprojected onto this ray.
  float zw = texelFetch(uSceneDepth, ivec2(pixel - uViewport.xy), 0).r;
  if (zw < 1.0)
  {
    vec4 s4 = uClipToLocal * vec4(ndc, 2.0 * zw - 1.0, 1.0);
    tExit = min(tExit, dot(s4.xyz / s4.w - o, d) / dot(d, d));
  }
  if (tEnter >= tExit)
  {
    return vec4(0.0);
  }
  inside = true;
  tFirst = tExit;
  //STRATA::Surfaces::Load
  tEnter = max(tEnter, tMin);

  // t spans the near-to-far segment [0, 1]; the sample lattice is t = (k + phase) dt.
  float segment = length(d);
  float dt = uSampleDistance / segment;

  //STRATA::Termination::Impl

  vec4 acc = vec4(0.0);
  //STRATA::Composite::Impl
  return acc;
}

void main()
{
  //STRATA::Rays::Impl
}
