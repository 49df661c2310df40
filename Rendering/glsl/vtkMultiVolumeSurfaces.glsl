// Strata multi-volume ray caster: the pixel's translucent surface layers (strata::VolumeSurfaceLayers),
// front to back, premultiplied, at their t on the ray (3e38: none). gSurfaceNext is the ray's
// first layer not composited yet: the ones before it went in with earlier fragments
// (uSurfaceProgress counts them). A layer goes in where the ray crosses it: the lattice step
// that contains it is split there.
uniform sampler2D uSurfaceProgress;
//STRATA::SurfaceSamplers::Dec
float gSurfaceT[@K@] = float[@K@](@K0@);
vec4 gSurfaceC[@K@] = vec4[@K@](@K0V@);
int gSurfaceNext = 0;
// Layer k of straight colour c at window depth z onto the ray o + t d through ndc.
void strataSurfaceSet(int k, vec4 c, float z, vec2 ndc, vec3 o, vec3 d)
{
  gSurfaceT[k] = 3.0e38;
  gSurfaceC[k] = vec4(c.rgb * c.a, c.a);
  if (z < 1.0)
  {
    vec4 s4 = uClipToLocal * vec4(ndc, 2.0 * z - 1.0, 1.0);
    gSurfaceT[k] = dot(s4.xyz / s4.w - o, d) / dot(d, d);
  }
}
// Composites the pending layers at or in front of t, nearest first.
void strataSurfacesBefore(float t, inout vec4 acc)
{
  for (int k = 0; k < @K@; ++k)
  {
    if (k >= gSurfaceNext)
    {
      if (gSurfaceT[k] > t)
      {
        return;
      }
      acc += (1.0 - acc.a) * gSurfaceC[k];
      gSurfaceNext = k + 1;
    }
  }
}
// The t of the nearest pending layer.
float strataSurfaceNext()
{
  for (int k = 0; k < @K@; ++k)
  {
    if (k == gSurfaceNext)
    {
      return gSurfaceT[k];
    }
  }
  return 3.0e38;
}
