/* libFuzzer harness: arbitrary text through the walk-scenario parser
 * (sim_scenario_parse, tools/world/sim.c): every key, the `other` robots,
 * events, comments, long lines.  A parse that succeeds must pass sim_init,
 * write back to text that parses to the identical struct, and walk a few
 * steps (observations within FL_OBS_MAX, occlusion by the other robots
 * included). */
#include "world/sim.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[128], *buf = NULL;
    size_t len = 0;
    static sim_scenario_t sc, back;
    static sim_t sim;
    static sim_step_t st;
    FILE *f;
    int k;
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    if (sim_scenario_parse(&sc, text, err, (int)sizeof err) == 0) {
        if (sc.n_others < 0 || sc.n_others > SIM_MAX_OTHERS || sim_init(&sim, &sc) != 0)
            abort();
        f = open_memstream(&buf, &len);
        if (f == NULL || sim_scenario_write(f, &sc) != 0)
            abort();
        fclose(f);
        if (sim_scenario_parse(&back, buf, err, (int)sizeof err) != 0 ||
            memcmp(&sc, &back, sizeof sc) != 0)
            abort();
        free(buf);
        for (k = 0; k < 5 && sim_step(&sim, &st); k++)
            if (st.obs.n > FL_OBS_MAX)
                abort();
    }
    free(text);
    return 0;
}
