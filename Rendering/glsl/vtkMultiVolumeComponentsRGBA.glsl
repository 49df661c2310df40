// Strata multi-volume ray caster: volume @n@'s four dependent components (IndependentComponents
// off): RGB the first three, over the scalars that map to 0 and 1 (as VTK 9.1's textures
// normalise the data type: strata::MultiVolumeInput::GetColorRange), clamped, and the extinction of
// the fourth from the transfer table.
uniform sampler2D uTransfer@n@;
uniform vec3 uTableRange@n@;
uniform vec3 uColorLo@n@;
uniform vec3 uColorScale@n@;
vec4 strataMedium@n@(vec3 p)
{
  vec4 s = strataComponents@n@(p);
  float tau = textureLod(uTransfer@n@, vec2((s.w - uTableRange@n@.x) * uTableRange@n@.y + uTableRange@n@.z, 0.5), 0.0).a;
  return vec4(clamp((s.xyz - uColorLo@n@) * uColorScale@n@, 0.0, 1.0), tau);
}
