# objrecall: one image for the API, the nightly ingestion and the grasp-validation worker (docker-compose.yml).
FROM python:3.11-slim

# MuJoCo's offscreen renderer on the CPU: EGL and OpenGL from Mesa (software rasteriser); curl for the
# healthcheck; tini reaps the ingestion child processes the API starts.
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      libegl1 libgl1 libgl1-mesa-dri libegl-mesa0 libosmesa6 curl tini \
 && rm -rf /var/lib/apt/lists/*

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    MUJOCO_GL=egl \
    PYOPENGL_PLATFORM=egl \
    OBJRECALL_DB=/data/catalog.duckdb

WORKDIR /app
COPY pyproject.toml README.md ./
COPY kb ./kb
COPY recall ./recall
COPY scrapers ./scrapers
COPY sim ./sim
COPY migrations ./migrations
COPY deploy ./deploy
RUN pip install --no-cache-dir . \
 && useradd --create-home --uid 10001 objrecall \
 && mkdir -p /data /config \
 && chown objrecall /data

USER objrecall
VOLUME ["/data"]
EXPOSE 8000
ENTRYPOINT ["/usr/bin/tini", "--"]
CMD ["objrecall", "serve", "--host", "0.0.0.0", "--port", "8000", "--db", "/data/catalog.duckdb"]
