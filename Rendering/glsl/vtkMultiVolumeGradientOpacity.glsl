// Strata multi-volume ray caster: gradient opacity of volume @n@. The gradient by central
// differences one voxel apart in index space, taken to the local frame (as shading does); its
// magnitude (scalar per world unit) reads the property's gradient opacity table, which scales the
// sample's opacity per unit distance: tau' = -ln(1 - go (1 - exp(-tau u))) / u.
uniform sampler2D uGradientOpacity@n@;
uniform vec3 uGradientRange@n@; // magnitude g -> texture coordinate (g - x) * y + z
uniform float uUnit@n@;
float strataGradientTau@n@(vec3 p, float tau)
{
  vec3 x = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  vec3 g = 0.5 * vec3(strataScalarAt@n@(x + vec3(1.0, 0.0, 0.0)) - strataScalarAt@n@(x - vec3(1.0, 0.0, 0.0)),
    strataScalarAt@n@(x + vec3(0.0, 1.0, 0.0)) - strataScalarAt@n@(x - vec3(0.0, 1.0, 0.0)),
    strataScalarAt@n@(x + vec3(0.0, 0.0, 1.0)) - strataScalarAt@n@(x - vec3(0.0, 0.0, 1.0)));
  g = transpose(mat3(uLocalToIndex@n@)) * g;
  float go = textureLod(uGradientOpacity@n@, vec2((length(g) - uGradientRange@n@.x) * uGradientRange@n@.y + uGradientRange@n@.z, 0.5), 0.0).r;
  float a = (1.0 - exp(-tau * uUnit@n@)) * clamp(go, 0.0, 1.0);
  return -log(max(1.0 - a, 1.0e-6)) / uUnit@n@;
}
