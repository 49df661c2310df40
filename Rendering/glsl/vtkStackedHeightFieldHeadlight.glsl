// Lighting complexity 1: one headlight.
  float df = max(0.0, normalVC.z);
  diffuse = df * lightColor0;
  // pow(x, 0) is undefined at x = 0: a power of 0 is a constant highlight.
  specular = (uSpecularPower > 0.0 ? pow(df, uSpecularPower) : 1.0) * lightColor0;
