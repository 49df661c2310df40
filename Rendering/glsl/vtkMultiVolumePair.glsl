// Pre-integrated overlap: each volume's segment as an optical depth and a mean colour; depths
// add, colours weighted by depth (exact for one volume, the physical mix for constant media).
vec4 strataPair(float sf[@K@], float sb[@K@], float len, vec3 mid)
{
  float X = 0.0;
  vec3 e = vec3(0.0);
  vec4 ca = vec4(0.0);
  float x = 0.0;
  //STRATA::PairVolumes::Impl
  float a = 1.0 - exp(-X);
  return X > 0.0 ? vec4(e / X * a, a) : vec4(0.0);
}
