// Colour per horizon: for horizon k, uColors[2k] = (first entry of its table, or -1 for its
// solid colour uColors[2k + 1]; attribute layer, or -1 for its depth; range low; table entries
// per unit, 1024 / (high - low), from the CPU in double).
// A table is 1024 entries over the range and one more for a value of no data.
uniform samplerBuffer uColors;
//STRATA::Attribute::Dec
vec3 strataHorizonColor(int layer, vec3 pGrid)
{
  vec4 d = texelFetch(uColors, 2 * layer);
  if (d.x < 0.0)
  {
    return texelFetch(uColors, 2 * layer + 1).rgb;
  }
  int table = int(d.x);
  float value = pGrid.z;
  //STRATA::Attribute::Impl
  float s = (value - d.z) * d.w;
  // Clamped in float: int() of a value beyond int's range (or Inf, NaN) is undefined.
  return texelFetch(uColors, table + int(clamp(s, 0.0, 1023.0))).rgb;
}
