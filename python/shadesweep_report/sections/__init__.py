"""One module per paper section; SECTIONS maps an experiment to its section."""
from .aa_translucency import section_aa_translucency
from .gbuffer_error import section_gbuffer_error
from .renderers_tiled import section_renderers_tiled
from .s000_coverage import section_s000_coverage
from .s000_drawcalls import section_s000_drawcalls
from .s000_illum import section_s000_illum
from .s000_resolution import section_s000_resolution
from .s000_stencil import section_s000_stencil
from .s003_exp1 import section_s003_exp1
from .s003_exp2 import section_s003_exp2


SECTIONS = {
    "s003-exp1": section_s003_exp1,
    "s003-exp2": section_s003_exp2,
    "s000-resolution": section_s000_resolution,
    "s000-drawcalls": section_s000_drawcalls,
    "s000-spot-coverage": lambda s: section_s000_coverage(s, "5.4.1 One spot light", "spot-coverage"),
    "s000-two-spots": lambda s: section_s000_coverage(s, "5.4.2 Two spotlights, overlapping",
                                                      "two-spots-overlap"),
    "s000-stencil": section_s000_stencil,
    "s000-illumination-sets": section_s000_illum,
    "gbuffer-error": section_gbuffer_error,
    "renderers-tiled": section_renderers_tiled,
    "aa-translucency": section_aa_translucency,
}
