// A Gaussian of standard deviation sigma = size / sqrt(2 pi) integrates to size^2, the
  // square's area; the sprite spans +- 3 sigma.
  float px = max(size, 1.0);
  vSigma = px * 0.3989422804;
  vSide = ceil(6.0 * vSigma);
  gl_PointSize = vSide;
  vColor = vec4(c, a) * min(size * size / (px * px), 1.0);
