{
    vec3 L = lightDirectionVC@l@;
    float att = 1.0;
    //STRATA::Positional::Impl
    float df = max(0.0, dot(normalVC, -L));
    diffuse += att * df * lightColor@l@;
    if (df > 0.0)
      specular += att * (uSpecularPower > 0.0 ? pow(max(0.0, dot(reflect(L, normalVC), viewDirectionVC)), uSpecularPower) : 1.0) * lightColor@l@;
  }
