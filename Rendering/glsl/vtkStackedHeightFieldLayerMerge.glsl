// The translucent horizons coincident with the hit (equal height at its point: touching
  // horizons) are one layer: composited in index order, as the references do at equal depth.
  float layerAlpha = 0.0;
  {
    vec2 muv = clamp(pGrid.xy - vec2(hitCell), 0.0, 1.0);
    vec4 hh = strataCorners(hitLayer, hitCell);
    float hHit = mix(mix(hh.x, hh.y, muv.x), mix(hh.z, hh.w, muv.x), muv.y);
    vec3 premultiplied = vec3(0.0);
    for (int l = 0; l < uNumHorizons; ++l)
    {
      float a = strataHorizonOpacity(l);
      if (a >= 1.0)
      {
        continue;
      }
      if (l != hitLayer)
      {
        vec4 hl = strataCorners(l, hitCell);
        if (any(strataHoles(hl))) // a hole is not coincident (tested on the bits, not by NaN)
        {
          continue;
        }
        float h = mix(mix(hl.x, hl.y, muv.x), mix(hl.z, hl.w, muv.x), muv.y);
        if (abs(h - hHit) > uZEps)
        {
          continue;
        }
      }
      vec3 c = l == hitLayer ? baseColor : strataLayerColor(l, pGrid);
      premultiplied += (1.0 - layerAlpha) * a * c;
      layerAlpha += (1.0 - layerAlpha) * a;
    }
    baseColor = premultiplied / max(layerAlpha, 1.0e-30);
  }
