"""``matloom studio``: a browser workspace to see, edit, compare and export a material program.

A small Starlette app (:mod:`matloom.studio.app`) served by uvicorn on 127.0.0.1
(:mod:`matloom.studio.server`), in the optional ``[studio]`` extra; the front end is built from
``studio-web/`` into ``matloom/studio/static/``. The HTTP API, the maps wire format and the
security rules are docs/studio-api.md. Importing this package imports neither Starlette nor
uvicorn.
"""
