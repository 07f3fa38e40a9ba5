import os
from pathlib import Path

import pytest

from grammar_lang.blas import pin_blas_threads

# As the CLIs do: BLAS threads spin on the solver's small matrices.
pin_blas_threads()

ROOT = Path(__file__).resolve().parent.parent
# The corpus lives beside the repository (../shared/corpus); GG_CORPUS overrides.
CORPUS = Path(os.environ.get("GG_CORPUS", ROOT.parent / "shared" / "corpus" / "examples"))
# The paper's illustrations sit beside the corpus examples (so GG_CORPUS moves both).
ILLUSTRATIONS = CORPUS.parent / "illustrations"


def corpus_names() -> list[str]:
    names = sorted(p.stem for p in CORPUS.glob("*.svg"))
    if not names:
        # Never let a missing corpus turn corpus tests into zero silent parametrizations.
        raise RuntimeError(f"corpus not found at {CORPUS}; set GG_CORPUS to its examples folder")
    return names


@pytest.fixture(scope="session")
def corpus_dir() -> Path:
    if not CORPUS.is_dir():
        pytest.fail(f"corpus not found at {CORPUS}; set GG_CORPUS")
    return CORPUS
