"""Type stubs of `close.vrfolding`."""

import os
from typing import Iterator, List, Union

from . import Sample

class Store:
    """An open VR-Folding store: its usable fold actions as `Sample`s."""

    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[Sample]: ...
    def __getitem__(self, k: int) -> Sample: ...
    @property
    def path(self) -> str: ...
    @property
    def dropped(self) -> int:
        """Folds left out because a mesh they use is broken."""
    @property
    def errors(self) -> List[str]:
        """Videos that could not be read."""

def open(store: Union[str, os.PathLike[str]]) -> Store: ...
