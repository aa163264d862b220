"""``python -m kb.service.cli`` runs the ``objrecall`` command line."""

from kb.service.cli import main

main()
