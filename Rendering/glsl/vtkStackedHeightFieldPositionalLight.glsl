// Lighting complexity 3: positional lights and spots.
    if (lightPositional@l@ != 0)
    {
      vec3 toP = posVC - lightPositionVC@l@;
      float dist = length(toP);
      // A light at the hit point shines along its own direction (normalize(0) is NaN).
      L = dist > 0.0 ? toP / dist : lightDirectionVC@l@;
      float coneDot = dot(L, lightDirectionVC@l@);
      att = 1.0 / (lightAttenuation@l@.x + lightAttenuation@l@.y * dist + lightAttenuation@l@.z * dist * dist);
      if (lightConeAngle@l@ < 90.0)
        att *= coneDot >= cos(radians(lightConeAngle@l@)) ? pow(coneDot, lightExponent@l@) : 0.0;
    }
