// The hit cell's bilinear patch gives the normal; lit two-sided.
  vec4 hc = strataCorners(hitLayer, hitCell);
  vec2 huv = clamp(pGrid.xy - vec2(hitCell), 0.0, 1.0);
  vec3 nGrid = vec3(-mix(hc.y - hc.x, hc.w - hc.z, huv.y), -mix(hc.z - hc.x, hc.w - hc.y, huv.x), 1.0);
  vec3 normalVC = normalize(uNormalMatrix * nGrid);
  vec3 posVC = (uGridToView * vec4(pGrid, 1.0)).xyz;
  vec3 viewDirectionVC = uParallel != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-posVC);
  if (dot(normalVC, viewDirectionVC) < 0.0) normalVC = -normalVC; // two-sided
  vec3 diffuse = vec3(0.0), specular = vec3(0.0);
  //STRATA::Lights::Impl
  vec3 shadedColor = uAmbient * baseColor + uDiffuse * diffuse * baseColor + uSpecular * specular * uSpecularColor;
