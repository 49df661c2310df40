tf = textureLod(uTransfer@n@, vec2((strataScalar@n@(p) - uTableRange@n@.x) * uTableRange@n@.y + uTableRange@n@.z, 0.5), 0.0);
  //STRATA::Shade::Impl
  e += tf.rgb * tf.a;
  tau += tf.a;
