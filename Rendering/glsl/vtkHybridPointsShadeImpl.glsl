vec3 N = normalize(uNormalToWorld * pointNormal);
  vec3 diffuse = vec3(0.0);
  vec3 specular = vec3(0.0);
  for (int l = 0; l < uNumLights; ++l)
  {
    diffuse += abs(dot(N, uLightDirection[l])) * uLightColor[l];
    specular += pow(abs(dot(N, normalize(uLightDirection[l] + uViewDirection))), uMaterial.w) * uLightColor[l];
  }
  c = c * (uMaterial.x + uMaterial.y * diffuse) + uMaterial.z * specular * a;
