"""The faces of objrecall, the top floor of the house: the ``objrecall`` command line (:mod:`kb.service.cli`),
the HTTP service and its web page (:mod:`kb.service.http`) and the main job (:mod:`kb.service.mainjob`).

These modules may import every package (``kb`` storage, ``recall``, ``scrapers``, ``sim``); nothing below
them imports them (``tests/test_layering.py`` checks it). Importing this package imports nothing else.
"""
