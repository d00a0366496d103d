"""``python -m pinframes.cli``: the same as the ``pinframes`` command."""

from . import main

raise SystemExit(main())
