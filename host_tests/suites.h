/* Every suite, in run order.  Add one line per host_tests/test_<stage>.c. */
T_SUITE(fixed);
T_SUITE(image);
T_SUITE(camera);
T_SUITE(field);
T_SUITE(obs);
T_SUITE(render);
T_SUITE(sim);
T_SUITE(realdata);
T_SUITE(color);
T_SUITE(scan);
T_SUITE(fuzzy);
T_SUITE(lines);
T_SUITE(features);
T_SUITE(adversarial);
T_SUITE(walks);
T_SUITE(fuzz_regress);
T_SUITE(rules);
