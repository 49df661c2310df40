// Attribute grids on the stack's lateral grid, one array layer each; no data is NaN.
uniform sampler2DArray uAttributes;
// Bilinear over the valid corners of the cell at g, their weights renormalised (a point on a
// hole corner: the mean of the valid ones); false when all four are holes
// (strata::HeightFieldStack::Interpolate).
bool strataAttribute(int layer, vec2 g, out float value)
{
  value = 0.0; // written on every path (an out parameter is copied back even when not set)
  g = clamp(g, vec2(0.0), uGridMax);
  ivec2 c = min(ivec2(g), ivec2(uGridMax) - 1);
  vec2 uv = g - vec2(c);
  vec4 a = vec4(texelFetch(uAttributes, ivec3(c, layer), 0).r,
    texelFetch(uAttributes, ivec3(c + ivec2(1, 0), layer), 0).r,
    texelFetch(uAttributes, ivec3(c + ivec2(0, 1), layer), 0).r,
    texelFetch(uAttributes, ivec3(c + ivec2(1, 1), layer), 0).r);
  vec4 w = vec4((1.0 - uv.x) * (1.0 - uv.y), uv.x * (1.0 - uv.y), (1.0 - uv.x) * uv.y, uv.x * uv.y);
  bvec4 ok = not(strataIsNaN(a)); // on the bits, as strata::HeightFieldStack::Interpolate's isnan
  a = mix(vec4(0.0), a, ok); // a selection, so a NaN corner leaves no NaN behind
  vec4 valid = vec4(ok);
  float weight = dot(w, valid);
  float count = dot(valid, vec4(1.0));
  if (count == 0.0)
  {
    return false;
  }
  value = weight > 0.0 ? dot(w, a) / weight : dot(a, vec4(1.0)) / count;
  return true;
}
