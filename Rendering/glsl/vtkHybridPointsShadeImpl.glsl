// A zero normal (no normal) lights nothing but the ambient term: normalize(0) is NaN.
  vec3 n = uNormalToWorld * pointNormal;
  float nn = dot(n, n);
  vec3 N = nn > 0.0 ? n * inversesqrt(nn) : vec3(0.0);
  vec3 diffuse = vec3(0.0);
  vec3 specular = vec3(0.0);
  for (int l = 0; l < uNumLights; ++l)
  {
    diffuse += abs(dot(N, uLightDirection[l])) * uLightColor[l];
    // As the volumes' shading: no highlight where L + V is zero, pow(x, 0) taken as 1.
    vec3 H = uLightDirection[l] + uViewDirection;
    float HH = dot(H, H);
    float NH = HH > 1.0e-12 ? abs(dot(N, H)) * inversesqrt(HH) : 0.0;
    specular += (uMaterial.w > 0.0 ? pow(NH, uMaterial.w) : 1.0) * uLightColor[l];
  }
  c = c * (uMaterial.x + uMaterial.y * diffuse) + uMaterial.z * specular * a;
