// Strata multi-volume ray caster: shading of volume @n@. Gradient by central differences one
// voxel apart in index space, taken to the local frame by the transpose of the local -> index
// Jacobian; lit two-sided (a volume's gradient has no inside), Blinn-Phong with the scene's
// lights (declared once for all volumes).
uniform vec4 uMaterial@n@; // ambient, diffuse, specular, specular power
vec3 strataShade@n@(vec3 p, vec3 color)
{
  vec3 x = (uLocalToIndex@n@ * vec4(p, 1.0)).xyz;
  vec3 g = 0.5 * vec3(strataScalarAt@n@(x + vec3(1.0, 0.0, 0.0)) - strataScalarAt@n@(x - vec3(1.0, 0.0, 0.0)),
    strataScalarAt@n@(x + vec3(0.0, 1.0, 0.0)) - strataScalarAt@n@(x - vec3(0.0, 1.0, 0.0)),
    strataScalarAt@n@(x + vec3(0.0, 0.0, 1.0)) - strataScalarAt@n@(x - vec3(0.0, 0.0, 1.0)));
  g = transpose(mat3(uLocalToIndex@n@)) * g;
  float len = length(g);
  vec4 m = uMaterial@n@;
  if (len <= 0.0)
  {
    return color * (m.x + m.y);
  }
  vec3 N = g / len;
  vec3 diffuse = vec3(0.0);
  vec3 specular = vec3(0.0);
  for (int l = 0; l < uNumLights; ++l)
  {
    diffuse += abs(dot(N, uLightDirection[l])) * uLightColor[l];
    // No NaN from the GPU's corner cases: L + V is zero for a light straight against the view
    // (no highlight; normalize(0) is NaN), and pow(x, 0) is undefined at x = 0 (a power of 0 is
    // a constant highlight).
    vec3 H = uLightDirection[l] + gViewDirection;
    float HH = dot(H, H);
    float NH = HH > 1.0e-12 ? abs(dot(N, H)) * inversesqrt(HH) : 0.0;
    specular += (m.w > 0.0 ? pow(NH, m.w) : 1.0) * uLightColor[l];
  }
  return color * (m.x + m.y * diffuse) + m.z * specular;
}
