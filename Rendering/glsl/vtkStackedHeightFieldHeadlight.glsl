// Lighting complexity 1: one headlight.
  float df = max(0.0, normalVC.z);
  diffuse = df * lightColor0;
  specular = pow(df, uSpecularPower) * lightColor0;
