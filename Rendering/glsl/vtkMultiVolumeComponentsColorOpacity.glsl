// Strata multi-volume ray caster: volume @n@'s two dependent components (IndependentComponents
// off): the colour of the first and the extinction of the second, both from the transfer table.
uniform sampler2D uTransfer@n@;
uniform vec3 uTableRange@n@;
vec4 strataMedium@n@(vec3 p)
{
  vec2 s = strataComponents@n@(p).xy;
  vec2 x = (s - uTableRange@n@.x) * uTableRange@n@.y + uTableRange@n@.z;
  return vec4(textureLod(uTransfer@n@, vec2(x.x, 0.5), 0.0).rgb, textureLod(uTransfer@n@, vec2(x.y, 0.5), 0.0).a);
}
