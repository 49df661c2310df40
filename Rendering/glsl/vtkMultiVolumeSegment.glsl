// Post-classification: emission and extinction of the mixed media at p, one lattice step of
// length len (extinctions add, emission is weighted by extinction).
vec4 strataSegment(vec3 p, float len)
{
  vec3 e = vec3(0.0);
  float tau = 0.0;
  vec4 tf = vec4(0.0);
  //STRATA::SegmentVolumes::Impl
  float a = 1.0 - exp(-tau * len);
  return tau > 0.0 ? vec4(e / tau * a, a) : vec4(0.0);
}
