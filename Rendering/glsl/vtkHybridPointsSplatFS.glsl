vec2 r = (gl_PointCoord - 0.5) * vSide;
  gl_FragData[0] = vColor * exp(-dot(r, r) / (2.0 * vSigma * vSigma));
