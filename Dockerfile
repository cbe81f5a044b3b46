# discreel image: `docker build -t discreel .`, then the service (docs/serve.md)
#   docker run -p 8080:8080 -v discreel-data:/data discreel
# or one render
#   docker run --rm -u "$(id -u):$(id -g)" -v "$PWD:/work" discreel render -o /work/demo.mp4
# See docs/container.md (also for building and running without Docker, with buildah).

# Build stage: the same set-up script a developer runs, then the test suite. The container
# test is left out: it builds this very image; so are the `arch` tests, which build physics
# again in other configurations and need the cross tools only `setup.sh test` installs, and
# the `browser` and `slurm` tests, which need chromium and Slurm.
FROM debian:bookworm-slim AS build
WORKDIR /src
# setup.sh alone first, so the package layer is cached until the package list changes.
COPY setup.sh ./
RUN bash setup.sh deps && rm -rf /var/lib/apt/lists/*
COPY . .
RUN bash setup.sh build \
 && ctest --test-dir build --output-on-failure --parallel "$(nproc)" --label-exclude '^(container|arch|browser|slurm)$'

# Runtime stage: the binary and the shared libraries it links (from its ldd), nothing else.
FROM debian:bookworm-slim
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      libosmesa6 libavcodec59 libavformat59 libswscale6 libavutil57 libyaml-cpp0.7 \
      libsqlite3-0 libfreetype6 fonts-dejavu-core \
 && rm -rf /var/lib/apt/lists/*
COPY --from=build /src/build/bin/discreel /usr/local/bin/discreel
# Fail the image build, not the first user, if a library is missing from the list above.
RUN if ldd /usr/local/bin/discreel | grep 'not found'; then exit 1; fi
RUN useradd --create-home --uid 1000 --user-group discreel \
 && mkdir /work /data && chown discreel:discreel /work /data
USER discreel
WORKDIR /work
# The jobs and outputs of the service: keep them on a volume and they survive the container.
VOLUME /data
EXPOSE 8080
# bash's /dev/tcp: the image needs no HTTP client for its own health check.
HEALTHCHECK --interval=30s --timeout=5s --start-period=10s --retries=3 \
  CMD ["bash", "-c", "exec 3<>/dev/tcp/127.0.0.1/8080 && printf 'GET /healthz HTTP/1.0\\r\\n\\r\\n' >&3 && head -n 1 <&3 | grep -q ' 200 '"]
ENTRYPOINT ["discreel"]
CMD ["serve", "--listen", "0.0.0.0:8080", "--data", "/data"]
