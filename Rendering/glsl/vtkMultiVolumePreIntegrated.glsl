// Strata multi-volume ray caster: volume @n@'s segment from its full pre-integration table
// (strata::PreIntegrationTable, M x M entries at the sample distance uPreStep), x = (s - min) *
// scale in [0, 1] over the table's scalar range, read bilinearly at texel centres.
uniform sampler2D uPreTable@n@;
uniform vec3 uPreRange@n@; // min, scale, M
uniform float uPreStep@n@;
vec4 strataPre@n@(float sf, float sb, float len)
{
  vec2 x = clamp((vec2(sf, sb) - uPreRange@n@.x) * uPreRange@n@.y, 0.0, 1.0);
  float m = uPreRange@n@.z;
  vec4 ca = textureLod(uPreTable@n@, (x * (m - 1.0) + 0.5) / m, 0.0);
  if (len != uPreStep@n@)
  {
    // A step cut short by a fragment face: opacity corrected to its length.
    float a = 1.0 - pow(max(1.0 - ca.a, 0.0), len / uPreStep@n@);
    ca = vec4(ca.a > 0.0 ? ca.rgb * (a / ca.a) : vec3(0.0), a);
  }
  return ca;
}
