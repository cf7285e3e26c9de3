// Renders the default scene, small, through an installed thalassa and checks the image.
#include <cmath>
#include <cstdio>

#include <thalassa/thalassa.hpp>

int main() {
  thalassa::SceneBuilder builder;
  builder.set("image.width=40");
  builder.set("image.height=30");
  const thalassa::Scene scene = builder.build();
  auto context = thalassa::create_headless_context();
  thalassa::Renderer renderer(*context, scene);
  renderer.render();
  const thalassa::Image image = renderer.image();
  double total = 0;
  for (float v : image.rgba) {
    if (!std::isfinite(v)) return 1;
    total += v;
  }
  std::printf("consumer: thalassa %s rendered %dx%d, mean %.4g\n", THALASSA_VERSION_STRING,
              image.width, image.height, total / image.rgba.size());
  return image.width == 40 && image.height == 30 && total > 0 ? 0 : 1;
}
