# Whirl: multi-stage build, small non-root runtime image.
#   docker build -t whirl .
#   docker run -p 8080:8080 whirl

FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
# Dependencies first, in their own layer, so that source edits rebuild only the crate.
COPY Cargo.toml Cargo.lock ./
RUN mkdir src benches && echo 'fn main() {}' > src/main.rs && echo '' > src/lib.rs \
    && echo 'fn main() {}' > benches/speed.rs \
    && cargo build --release --locked \
    && rm -rf src benches target/release/deps/whirl* target/release/deps/libwhirl* target/release/whirl*
COPY src src
COPY benches benches
COPY migrations migrations
# The OpenAPI document's request examples are compiled in (src/service/openapi/examples.rs).
COPY examples examples
# The plots' font (PNG), compiled in: the runtime image has no fonts.
COPY assets assets
RUN cargo build --release --locked --bin whirl && strip target/release/whirl

FROM debian:bookworm-slim
LABEL org.opencontainers.image.title="whirl" \
      org.opencontainers.image.description="Rotordynamics computation service: Campbell diagrams, stability, time and unbalance responses, API 684 audits, with hysteretic damping treated properly" \
      org.opencontainers.image.licenses="MIT"
# A numeric user and group: Kubernetes' runAsNonRoot can verify it without /etc/passwd.
RUN groupadd --system --gid 10001 whirl \
    && useradd --system --uid 10001 --gid 10001 --no-create-home --shell /usr/sbin/nologin whirl \
    && mkdir /data && chown 10001:10001 /data
COPY --from=build /src/target/release/whirl /usr/local/bin/whirl
USER 10001:10001
# The embedded job store (SQLite) lives here unless WHIRL_DATABASE_URL names a PostgreSQL.
ENV HOST=0.0.0.0 PORT=8080 RUST_LOG=info WHIRL_DATA_DIR=/data
VOLUME /data
EXPOSE 8080
# The binary checks itself: no curl in the image.
HEALTHCHECK --interval=15s --timeout=3s --start-period=5s --retries=3 CMD ["whirl", "healthcheck"]
ENTRYPOINT ["whirl"]
