// Strata multi-volume ray caster: volume @n@'s segment by the two-integral form of
// pre-integration (strata::PreIntegrationTable's 1-D integral table, M entries, read with texelFetch
// and mixed in float: filter weights would be amplified by the division), any segment length.
// Colour is clamped at uPreMaxColor times the extinction.
uniform sampler2D uPreTable@n@;
uniform vec3 uPreRange@n@; // min, scale, M
uniform float uPreMaxColor@n@;
vec4 strataIntegral@n@(float x)
{
  float f = x * (uPreRange@n@.z - 1.0);
  int i0 = min(int(floor(f)), int(uPreRange@n@.z) - 2);
  return mix(texelFetch(uPreTable@n@, ivec2(i0, 0), 0), texelFetch(uPreTable@n@, ivec2(i0 + 1, 0), 0), f - float(i0));
}
vec4 strataPre@n@(float sf, float sb, float len)
{
  float xf = clamp((sf - uPreRange@n@.x) * uPreRange@n@.y, 0.0, 1.0);
  float xb = clamp((sb - uPreRange@n@.x) * uPreRange@n@.y, 0.0, 1.0);
  float h = 1.0 / (uPreRange@n@.z - 1.0);
  float w = max(abs(xb - xf), h);
  float lo = clamp(0.5 * (xf + xb) - 0.5 * w, 0.0, 1.0 - w);
  float hi = lo + w;
  vec4 d = strataIntegral@n@(hi) - strataIntegral@n@(lo);
  float tau = max(d.a / (hi - lo), 0.0);
  vec3 k = clamp(d.rgb / (hi - lo), vec3(0.0), vec3(uPreMaxColor@n@ * tau));
  float X = len * tau;
  float a = X < 0.01 ? X * (1.0 - X / 2.0 + X * X / 6.0) : 1.0 - exp(-X);
  vec3 c = X < 0.01 ? len * k * (1.0 - X / 2.0 + X * X / 6.0) : len * k * a / X;
  return vec4(c, a);
}
