// Empty-space skipping: from o + t d, moving along dir d (dir = 1 front to back, -1 back to
// front), the t at which the ray leaves the empty box around its cell in every volume (t
// itself if some volume's cell is visible). Cell c with distance D > 0 sits in the empty box
// of cells c - (D - 1) .. c + (D - 1), index coordinates [lo, hi] below.
float strataEmptyUntil(vec3 o, vec3 d, float t, float dir)
{
  float until = 3.0e38;
  vec3 x0 = vec3(0.0);
  vec3 dx = vec3(0.0);
  ivec3 c = ivec3(0);
  float D = 0.0;
  vec3 lo = vec3(0.0);
  vec3 hi = vec3(0.0);
  vec3 te = vec3(0.0);
  //STRATA::SkipVolumes::Impl
  return t + dir * until;
}
